// SPDX-License-Identifier: BSD-3-Clause
// lmk serve's page: wires the scene picker and the view to the capture, find and programs panels.
// `window.lmk` is the page's state for scripts and tests: lmk.ready resolves once the first scene
// is shown, lmk.project([x, y, z]) gives a scene point's place on the page, lmk.find.last holds
// the last search's result.
import {getJSON, upload} from '/app/api.js';
import {CapturePanel} from '/app/capture.js';
import {FindPanel} from '/app/find.js';
import {ProgramsPanel} from '/app/programs.js';
import {Viewer} from '/app/viewer.js';

class App {
  constructor(info) {
    this.info = info;
    this.sceneId = null;
    this.viewer = new Viewer(
        document.getElementById('view'), document.getElementById('labels'),
        document.getElementById('tooltip'));
    this.capture = new CapturePanel(this);
    this.find = new FindPanel(this, info);
    this.programs = new ProgramsPanel(this);
    this.picker = document.getElementById('scene-select');
    this.picker.addEventListener('change', () => this.showScene(this.picker.value));
    document.getElementById('upload').addEventListener('change', (e) => this.upload(e.target));
    this.listenForClicks();
  }

  status(text, error = false) {
    const s = document.getElementById('status');
    s.textContent = text;
    s.className = error ? 'error' : '';
  }

  /** One line per error term of a match, for tooltips. */
  termsText(match) {
    return Object.entries(match.terms || {})
        .map(([k, v]) => `${k}: ${typeof v === 'number' ? +v.toPrecision(4) : v}`)
        .join('\n');
  }

  project(point) {
    return this.viewer.project(point);
  }

  async loadScenes(select) {
    const {scenes} = await getJSON('/api/scenes');
    this.picker.replaceChildren();
    for (const s of scenes) {
      this.picker.add(new Option(`${s.name}${s.source === 'upload' ? ' (uploaded)' : ''}`, s.id));
    }
    const id = select || (scenes[0] && scenes[0].id);
    if (!id) {
      this.status('no scene: start lmk serve with scene files, or upload one');
      return;
    }
    this.picker.value = id;
    await this.showScene(id);
  }

  async showScene(id) {
    this.status('loading the scene…');
    const [info, cloud] =
        await Promise.all([getJSON(`/api/scenes/${id}`), getJSON(`/api/scenes/${id}/cloud`)]);
    this.sceneId = id;
    this.capture.sceneChoices(this.picker);
    this.viewer.setCloud(cloud, info);
    this.viewer.clear('matches');
    this.viewer.clear('targets');
    document.getElementById('scene-info').textContent =
        `${info.finite_points} points${
            cloud.stride > 1 ? ` (every ${cloud.stride}th shown)` : ''}` +
        `, ${info.has_rgb ? 'RGB' : 'coloured by height'}` +
        `${info.base_frame ? ', robot base frame' : ''}; sensor at ` +
        info.sensor.position.map((v) => v.toFixed(2)).join(', ');
    this.status(`${info.name}: click an object to capture it`);
  }

  async upload(input) {
    const file = input.files[0];
    if (!file) return;
    this.status(`uploading ${file.name}…`);
    try {
      const scene = await upload(file);
      await this.loadScenes(scene.id);
    } catch (e) {
      this.status(e.message, true);
    }
    input.value = '';
  }

  // A click (not a drag of the view or of a handle) on the cloud asks for a box guess there.
  listenForClicks() {
    const canvas = this.viewer.renderer.domElement;
    let down = null;
    canvas.addEventListener('pointerdown', (e) => {
      down = {x: e.clientX, y: e.clientY};
    });
    canvas.addEventListener('pointerup', (e) => {
      const click = down && Math.hypot(e.clientX - down.x, e.clientY - down.y) < 4;
      down = null;
      if (!click || this.viewer.handles.dragging || this.viewer.handles.axis !== null) return;
      const point = this.viewer.pick(e);
      if (point) this.capture.guessAt(point);
    });
  }
}

async function main() {
  const info = await getJSON('/api/info');
  document.getElementById('version').textContent = info.version;
  const app = new App(info);
  window.lmk = app;
  await Promise.all([app.find.loadLandmarks(), app.programs.load()]);
  await app.loadScenes();
}

window.lmkReady = main().catch((e) => {
  const s = document.getElementById('status');
  s.textContent = `the page could not start: ${e.message}`;
  s.className = 'error';
  throw e;
});
