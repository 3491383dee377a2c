// SPDX-License-Identifier: BSD-3-Clause
// The capture panel: a first box from a clicked point (POST /api/guess), the box's numbers
// editable beside its handles, the distinctiveness verdict (POST /api/check) before anything is
// written, then the landmark saved into the library (POST /api/landmarks).
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
    this.name = document.getElementById('landmark-name');
    this.name.addEventListener('input', () => this.invalidate());
    document.getElementById('new-box').addEventListener('click', () => this.startBox());
    document.getElementById('check').addEventListener('click', () => this.check());
    document.getElementById('save').addEventListener('click', () => this.save());
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
    const key = JSON.stringify([this.box, this.name.value.trim()]);
    if (key !== this.verdictFor) {
      document.getElementById('save').disabled = true;
      document.getElementById('save').textContent = 'Save';
      document.getElementById('verdict').textContent = ready ? 'check it before saving' : '';
    }
  }

  async check() {
    const name = this.name.value.trim();
    const key = JSON.stringify([this.box, name]);
    const verdict = document.getElementById('verdict');
    verdict.textContent = 'searching it in its own scene…';
    try {
      const v = await runJob('/api/check', {scene: this.app.sceneId, box: this.box, name});
      verdict.className = v.distinctive ? 'small good' : 'small warn';
      verdict.textContent = v.message;
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
        scene: this.app.sceneId,
        box: this.box,
        name,
        overwrite: document.getElementById('overwrite').checked,
      });
      this.app.status(`wrote ${saved.file}: ${saved.points} points`);
      document.getElementById('save').disabled = true;
      await this.app.find.loadLandmarks(name);
    } catch (e) {
      this.app.status(e.message, true);
    }
  }
}
