// SPDX-License-Identifier: BSD-3-Clause
// The capture panel: a first box from a clicked point (POST /api/guess), the box's numbers
// editable beside its handles, further views of the landmark from other scenes ("Add a view":
// registered onto this scene by the server, as `lmk capture A B`), the distinctiveness verdict
// (POST /api/check) before anything is written, then the landmark saved into the library
// (POST /api/landmarks).
import {postJSON, runJob} from '/app/api.js';
import * as THREE from '/three/build/three.module.js';

const DEG = Math.PI / 180;

// Box <-> the fields' centre, roll/pitch/yaw in degrees (R = Rz(yaw) Ry(pitch) Rx(roll), as the
// CLI's --box-rpy) and size.
function boxToFields(box) {
  const [w, x, y, z] = box.quaternion;
  const e = new THREE.Euler().setFromQuaternion(new THREE.Quaternion(x, y, z, w), 'ZYX');
  return {
    cx: box.position[0],
    cy: box.position[1],
    cz: box.position[2],
    roll: e.x / DEG,
    pitch: e.y / DEG,
    yaw: e.z / DEG,
    sx: box.size[0],
    sy: box.size[1],
    sz: box.size[2],
  };
}

function fieldsToBox(f) {
  const q = new THREE.Quaternion().setFromEuler(
      new THREE.Euler(f.roll * DEG, f.pitch * DEG, f.yaw * DEG, 'ZYX'));
  return {
    position: [f.cx, f.cy, f.cz],
    quaternion: [q.w, q.x, q.y, q.z],
    size: [f.sx, f.sy, f.sz],
  };
}

export class CapturePanel {
  constructor(app) {
    this.app = app;
    this.box = null;
    this.verdictFor = null;  // the JSON of the box and name the verdict was given for
    this.inputs = [...document.querySelectorAll('[data-box]')];
    for (const input of this.inputs) input.addEventListener('change', () => this.fromFields());
    for (const b of document.querySelectorAll('[data-mode]')) {
      b.addEventListener('click', () => {
        document.querySelectorAll('[data-mode]').forEach((x) => x.classList.toggle('on', x === b));
        app.viewer.setHandleMode(b.dataset.mode);
      });
    }
    this.views = [];  // further scenes' ids, fused after the shown scene's
    this.viewScene = document.getElementById('view-scene');
    document.getElementById('add-view').addEventListener('click', () => this.addView());
    document.getElementById('clear-views').addEventListener('click', () => this.setViews([]));
    this.name = document.getElementById('landmark-name');
    this.name.addEventListener('input', () => this.invalidate());
    document.getElementById('new-box').addEventListener('click', () => this.startBox());
    document.getElementById('check').addEventListener('click', () => this.check());
    document.getElementById('save').addEventListener('click', () => this.save());
  }

  /** The scenes that can add a view: every scene but the shown one. Called when scenes change. */
  sceneChoices(picker) {
    this.viewScene.replaceChildren();
    for (const o of picker.options) {
      if (o.value !== this.app.sceneId) this.viewScene.add(new Option(o.text, o.value));
    }
    this.setViews([]);  // views of another scene's box mean nothing here
  }

  addView() {
    const id = this.viewScene.value;
    if (!id || this.views.includes(id)) return;
    this.setViews([...this.views, id]);
  }

  setViews(views) {
    this.views = views;
    const names = views.map((id) => [...this.viewScene.options].find((o) => o.value === id).text);
    document.getElementById('views').textContent = views.length === 0 ?
        'one view: this scene' :
        `${views.length + 1} views: this scene, then ${names.join(', ')} (registered onto it)`;
    document.getElementById('clear-views').disabled = views.length === 0;
    this.invalidate();
  }

  // What every capture request says of the landmark: the scene, its further views, the box.
  request(name) {
    const body = {scene: this.app.sceneId, box: this.box, name};
    if (this.views.length > 0) body.views = this.views;
    return body;
  }

  /** A click in the view: the server's first guess of the box of the object under it. */
  async guessAt(point) {
    this.app.status(`guessing the box at ${point.map((v) => v.toFixed(3)).join(', ')}…`);
    try {
      const guess = await postJSON('/api/guess', {scene: this.app.sceneId, point});
      this.setBox(guess.box);
      this.app.status(
          `box guessed around ${guess.object_points} points; adjust it, name it, check`);
    } catch (e) {
      this.app.status(e.message, true);
    }
  }

  // A 20 cm box at the orbit centre, for objects the guess cannot separate.
  startBox() {
    const t = this.app.viewer.orbit.target;
    this.setBox({position: t.toArray(), quaternion: [1, 0, 0, 0], size: [0.2, 0.2, 0.2]});
  }

  setBox(box) {
    this.box = box;
    this.app.viewer.editBox(box, (b) => {
      this.box = b;
      this.toFields();
      this.invalidate();
    });
    this.toFields();
    this.invalidate();
  }

  toFields() {
    const f = boxToFields(this.box);
    for (const input of this.inputs) input.value = (+f[input.dataset.box].toFixed(4)).toString();
  }

  fromFields() {
    const f = {};
    for (const input of this.inputs) f[input.dataset.box] = parseFloat(input.value);
    if (Object.values(f).some((v) => !Number.isFinite(v)) || f.sx <= 0 || f.sy <= 0 || f.sz <= 0) {
      this.app.status('the box needs numbers, and positive sizes', true);
      return;
    }
    this.setBox(fieldsToBox(f));
  }

  // A changed box or name needs a new verdict before it is saved.
  invalidate() {
    const ready = this.box && this.name.value.trim() !== '';
    document.getElementById('check').disabled = !ready;
    const key = JSON.stringify([this.box, this.name.value.trim(), this.views]);
    if (key !== this.verdictFor) {
      document.getElementById('save').disabled = true;
      document.getElementById('save').textContent = 'Save';
      document.getElementById('verdict').textContent = ready ? 'check it before saving' : '';
    }
  }

  async check() {
    const name = this.name.value.trim();
    const key = JSON.stringify([this.box, name, this.views]);
    const verdict = document.getElementById('verdict');
    verdict.textContent = 'searching it in its own scene…';
    try {
      const v = await runJob('/api/check', this.request(name));
      verdict.className = v.distinctive ? 'small good' : 'small warn';
      const registered = (v.registrations || []).map(
          (r) => `view ${r.view} registered: overlap ${Math.round(100 * r.overlap)}%, ` +
              `residual ${(1000 * r.residual).toFixed(1)} mm`);
      verdict.textContent = [v.message, ...registered].join('; ');
      const lookAlike = (m, i) => {
        return {box: m.box, label: `look-alike ${i + 1}`, tooltip: this.app.termsText(m)};
      };
      this.app.viewer.showBoxes(
          (v.other_instances || []).map((m, i) => ({...lookAlike(m, i), rejected: true})));
      this.verdictFor = key;
      const save = document.getElementById('save');
      save.disabled = false;
      save.textContent = v.distinctive ? 'Save' : 'Save anyway';
    } catch (e) {
      verdict.className = 'small bad';
      verdict.textContent = e.message;
    }
  }

  async save() {
    const name = this.name.value.trim();
    try {
      const saved = await postJSON('/api/landmarks', {
        ...this.request(name),
        overwrite: document.getElementById('overwrite').checked,
      });
      const views = saved.views > 1 ? ` from ${saved.views} views` : '';
      this.app.status(`wrote ${saved.file}: ${saved.points} points${views}`);
      document.getElementById('save').disabled = true;
      await this.app.find.loadLandmarks(name);
    } catch (e) {
      this.app.status(e.message, true);
    }
  }
}
