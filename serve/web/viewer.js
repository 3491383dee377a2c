// SPDX-License-Identifier: BSD-3-Clause
// The 3D view: the scene's points, its sensor, the box being drawn (with move, rotate and resize
// handles), the matches with their rank and error, and a program's gripper targets.
import * as THREE from '/three/build/three.module.js';
import {OrbitControls} from '/three/examples/jsm/controls/OrbitControls.js';
import {TransformControls} from '/three/examples/jsm/controls/TransformControls.js';

/** An API box {position, quaternion [w,x,y,z], size} as a three.js object's pose and scale. */
export function applyBox(object, box) {
  object.position.fromArray(box.position);
  const [w, x, y, z] = box.quaternion;
  object.quaternion.set(x, y, z, w);
  object.scale.fromArray(box.size);
}

/** The API box of an object posed and scaled by applyBox. */
export function boxOf(object) {
  const q = object.quaternion;
  return {
    position: object.position.toArray(),
    quaternion: [q.w, q.x, q.y, q.z],
    size: object.scale.toArray().map(Math.abs),
  };
}

// Height colouring for clouds without RGB: blue low to yellow high along the scene's up axis.
function heightColors(positions, up) {
  const n = positions.length / 3;
  const heights = new Float32Array(n);
  let lo = Infinity, hi = -Infinity;
  for (let i = 0; i < n; ++i) {
    const h =
        positions[3 * i] * up[0] + positions[3 * i + 1] * up[1] + positions[3 * i + 2] * up[2];
    heights[i] = h;
    lo = Math.min(lo, h);
    hi = Math.max(hi, h);
  }
  const colors = new Float32Array(3 * n);
  const c = new THREE.Color();
  for (let i = 0; i < n; ++i) {
    c.setHSL(0.66 - 0.5 * (heights[i] - lo) / Math.max(hi - lo, 1e-6), 0.8, 0.55);
    colors.set([c.r, c.g, c.b], 3 * i);
  }
  return colors;
}

function wireBox(color) {
  const group = new THREE.Group();
  const unit = new THREE.BoxBufferGeometry(1, 1, 1);
  group.add(
      new THREE.LineSegments(new THREE.EdgesGeometry(unit), new THREE.LineBasicMaterial({color})));
  const fill = new THREE.Mesh(
      unit,
      new THREE.MeshBasicMaterial({color, transparent: true, opacity: 0.12, depthWrite: false}));
  group.add(fill);
  group.userData.fill = fill;
  return group;
}

// A match's box colour: a rejected candidate dull red, a competing pose grey, a match by its
// confidence from red (0) through yellow to green (1), or plain green without one.
function boxColour(item) {
  if (item.rejected) return 0xcc6666;
  if (item.competitor) return 0x999999;
  if (item.confidence === null || item.confidence === undefined) return 0x66ff66;
  const p = Math.min(Math.max(item.confidence, 0), 1);
  return new THREE.Color(Math.min(1, 2 * (1 - p)), Math.min(1, 2 * p), 0.2).getHex();
}

// A parallel gripper at the end-effector frame: palm across y, fingers along +x.
function gripper(color, closed) {
  const gap = closed ? 0.02 : 0.08;
  const points = [
    [-0.06, 0, 0],
    [0, 0, 0],
    [0, -gap / 2, 0],
    [0, gap / 2, 0],
    [0, -gap / 2, 0],
    [0.05, -gap / 2, 0],
    [0, gap / 2, 0],
    [0.05, gap / 2, 0],
  ].map((p) => new THREE.Vector3(...p));
  return new THREE.LineSegments(
      new THREE.BufferGeometry().setFromPoints(points), new THREE.LineBasicMaterial({color}));
}

export class Viewer {
  constructor(container, labels, tooltip) {
    this.container = container;
    this.labels = labels;
    this.tooltip = tooltip;
    this.renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
    this.renderer.setPixelRatio(window.devicePixelRatio);
    container.prepend(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x181a1b);
    this.camera = new THREE.PerspectiveCamera(55, 1, 0.01, 100);
    this.orbit = new OrbitControls(this.camera, this.renderer.domElement);
    this.handles = new TransformControls(this.camera, this.renderer.domElement);
    this.handles.addEventListener('dragging-changed', (e) => {
      this.orbit.enabled = !e.value;
    });
    this.handles.addEventListener('objectChange', () => {
      if (this.onBoxChange) this.onBoxChange(boxOf(this.edited));
    });
    this.scene.add(this.handles);
    this.layers = {};
    for (const name of ['cloud', 'sensor', 'matches', 'targets', 'paths', 'edit']) {
      this.layers[name] = new THREE.Group();
      this.scene.add(this.layers[name]);
    }
    this.labelled = [];   // [{object, element}]: HTML labels that follow 3D points
    this.hoverable = [];  // [{mesh, text}]: tooltips on hover
    this.raycaster = new THREE.Raycaster();
    this.renderer.domElement.addEventListener('pointermove', (e) => this.hover(e));
    // Drawn on demand, not every frame: a cloud of a few hundred thousand points is slow to draw
    // in software (headless browsers, remote desktops), and an idle page should cost nothing.
    this.orbit.addEventListener('change', () => this.requestRender());
    this.handles.addEventListener('change', () => this.requestRender());
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  requestRender() {
    if (this.renderPending) return;
    this.renderPending = true;
    requestAnimationFrame(() => {
      this.renderPending = false;
      this.render();
    });
  }

  resize() {
    const w = this.container.clientWidth, h = this.container.clientHeight;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / Math.max(h, 1);
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
    for (const {object, element} of this.labelled) {
      const p = this.project(object.getWorldPosition(new THREE.Vector3()).toArray());
      element.style.display = p.visible ? '' : 'none';
      element.style.left = `${p.x - this.container.getBoundingClientRect().left}px`;
      element.style.top = `${p.y - this.container.getBoundingClientRect().top}px`;
    }
  }

  /** A scene point's position on the page, in CSS pixels (for labels, and for scripts). */
  project(point) {
    const v = new THREE.Vector3(...point).project(this.camera);
    const rect = this.renderer.domElement.getBoundingClientRect();
    return {
      x: rect.left + (v.x + 1) / 2 * rect.width,
      y: rect.top + (1 - v.y) / 2 * rect.height,
      visible: v.z > -1 && v.z < 1,
    };
  }

  /** Shows a cloud as /api/scenes/ID/cloud sends it, seen from its sensor. */
  setCloud(cloud, info) {
    this.clear('cloud');
    this.clear('sensor');
    const positions = Float32Array.from(cloud.positions, (v) => v / 1000);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    const colors = cloud.colors ? Float32Array.from(cloud.colors, (v) => v / 255) :
                                  heightColors(positions, info.up);
    geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
    geometry.computeBoundingSphere();
    this.points = new THREE.Points(
        geometry, new THREE.PointsMaterial({size: 2, sizeAttenuation: false, vertexColors: true}));
    this.layers.cloud.add(this.points);
    this.showSensor(info.sensor);
    this.lookFromSensor(info, geometry.boundingSphere);
    this.requestRender();
  }

  // The sensor: its axes and a small frustum along its optical axis (+z).
  showSensor(pose) {
    const frame = new THREE.Group();
    applyBox(frame, {...pose, size: [1, 1, 1]});
    frame.add(new THREE.AxesHelper(0.06));
    const d = 0.06, w = 0.04, h = 0.03;
    const corners = [[-w, -h, d], [w, -h, d], [w, h, d], [-w, h, d]];
    const lines = [];
    for (let i = 0; i < 4; ++i) {
      lines.push([0, 0, 0], corners[i], corners[i], corners[(i + 1) % 4]);
    }
    frame.add(new THREE.LineSegments(
        new THREE.BufferGeometry().setFromPoints(lines.map((p) => new THREE.Vector3(...p))),
        new THREE.LineBasicMaterial({color: 0x999999})));
    this.layers.sensor.add(frame);
    this.addLabel(frame, 'sensor');
  }

  // Start where the camera was, looking along its axis at the middle of the cloud, scene up up.
  lookFromSensor(info, sphere) {
    const origin = new THREE.Vector3(...info.sensor.position);
    const [w, x, y, z] = info.sensor.quaternion;
    const axis = new THREE.Vector3(0, 0, 1).applyQuaternion(new THREE.Quaternion(x, y, z, w));
    const depth = Math.max(0.5, sphere.center.clone().sub(origin).dot(axis));
    this.camera.up.fromArray(info.up);
    // Behind and above the sensor, so that the sensor shows small below the middle of the view.
    const up = new THREE.Vector3(...info.up);
    this.camera.position.copy(
        origin.clone().addScaledVector(axis, -0.3 * depth).addScaledVector(up, 0.15 * depth));
    this.orbit.target.copy(origin.clone().addScaledVector(axis, depth));
    this.camera.far = Math.max(100, 10 * sphere.radius);
    this.camera.updateProjectionMatrix();
    this.orbit.update();
  }

  /** Points the raycaster through the mouse event's position; the canvas's rectangle. */
  aimAt(event) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(
        (event.clientX - rect.left) / rect.width * 2 - 1,
        -(event.clientY - rect.top) / rect.height * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.camera);
    return rect;
  }

  /** The cloud point under a click, nearest the eye; null when the click hit no point. */
  pick(event) {
    if (!this.points) return null;
    this.aimAt(event);
    // A few pixels' width at the orbit target's distance.
    const distance = this.camera.position.distanceTo(this.orbit.target);
    this.raycaster.params.Points.threshold = 0.004 * distance;
    const hits = this.raycaster.intersectObject(this.points);
    return hits.length ? hits[0].point.toArray() : null;
  }

  /** The box being drawn, with handles; onChange(box) as they move it. */
  editBox(box, onChange) {
    this.clear('edit');
    this.handles.detach();
    this.requestRender();
    if (!box) return;
    const mesh = wireBox(0x33ccff);
    applyBox(mesh, box);
    this.layers.edit.add(mesh);
    this.edited = mesh;
    this.handles.attach(mesh);
    this.onBoxChange = onChange;
    this.requestRender();
  }

  setHandleMode(mode) {
    this.handles.setMode(mode);
    this.requestRender();
  }

  /** Draws matches [{box, label, tooltip, rejected}]. */
  showBoxes(items) {
    this.clear('matches');
    for (const item of items) {
      const mesh = wireBox(boxColour(item));
      applyBox(mesh, item.box);
      this.layers.matches.add(mesh);
      this.addLabel(mesh, item.label, 'matches');
      this.hoverable.push({mesh: mesh.userData.fill, text: item.tooltip, layer: 'matches'});
    }
    this.requestRender();
  }

  /** Draws a program's gripper targets [{pose, label, closed}]. */
  showTargets(targets) {
    this.clear('targets');
    for (const t of targets) {
      const frame = new THREE.Group();
      applyBox(frame, {...t.pose, size: [1, 1, 1]});
      frame.add(gripper(t.closed ? 0xff9933 : 0xffdd33, t.closed));
      frame.add(new THREE.AxesHelper(0.04));
      this.layers.targets.add(frame);
      this.addLabel(frame, t.label, 'targets');
    }
    this.requestRender();
  }

  /**
   * Draws the arms' swept paths [{points, around}] (the tool frame along each motion; a path
   * planned around an obstacle in orange) and, when a motion was refused, the place it would
   * touch {where, label} as a red ball.
   */
  showPaths(paths, contact) {
    this.clear('paths');
    for (const p of paths) {
      const geometry = new THREE.BufferGeometry().setFromPoints(
          p.points.map((q) => new THREE.Vector3(...q)));
      const colour = p.around ? 0xff8800 : 0x33ccff;
      this.layers.paths.add(new THREE.Line(geometry, new THREE.LineBasicMaterial({color: colour})));
    }
    if (contact) {
      const ball = new THREE.Mesh(
          new THREE.SphereGeometry(0.015, 16, 12), new THREE.MeshBasicMaterial({color: 0xff2222}));
      ball.position.set(...contact.where);
      this.layers.paths.add(ball);
      this.addLabel(ball, contact.label, 'paths');
    }
    this.requestRender();
  }

  /** Turns the view to the middle of `points`, from `distance` away, keeping its direction. */
  focus(points, distance) {
    if (points.length === 0) return;
    const centre = new THREE.Vector3();
    for (const p of points) centre.add(new THREE.Vector3(...p));
    centre.divideScalar(points.length);
    const back = this.camera.position.clone().sub(this.orbit.target).normalize();
    this.orbit.target.copy(centre);
    this.camera.position.copy(centre).addScaledVector(back, distance);
    this.orbit.update();
  }

  addLabel(object, text, layer = 'sensor') {
    const element = document.createElement('div');
    element.className = 'label';
    element.textContent = text;
    this.labels.append(element);
    this.labelled.push({object, element, layer});
  }

  clear(layer) {
    const group = this.layers[layer];
    while (group.children.length) group.remove(group.children[0]);
    this.labelled = this.labelled.filter((l) => {
      if (l.layer !== layer) return true;
      l.element.remove();
      return false;
    });
    this.hoverable = this.hoverable.filter((h) => h.layer !== layer);
    this.requestRender();
  }

  hover(event) {
    const rect = this.aimAt(event);
    const hit = this.raycaster.intersectObjects(this.hoverable.map((h) => h.mesh))[0];
    const item = hit && this.hoverable.find((h) => h.mesh === hit.object);
    this.tooltip.hidden = !item;
    if (item) {
      this.tooltip.textContent = item.text;
      this.tooltip.style.left = `${event.clientX - rect.left + 14}px`;
      this.tooltip.style.top = `${event.clientY - rect.top + 14}px`;
    }
  }
}
