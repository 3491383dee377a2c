// SPDX-License-Identifier: BSD-3-Clause
// The real-browser test of `lmk serve` (docs/serve.md, "Tests"): headless Chromium, driven through
// the DevTools protocol, loads a scene, clicks the carton (the real milk frame of ../shared/data,
// or the cup of a synthetic tabletop without it), accepts the guessed box, checks and captures
// it, runs find, and reads the matches from the page. They must equal `lmk find` on the same
// files. Screenshots are kept in the work directory, and must not be blank.
//
//   node browser_test.js LMK_BINARY WORK_DIR [SHARED_DATA_DIR]
//
// Exits 0 on success, 1 on failure, 77 (skipped) when chromium or node-ws is missing.
'use strict';
const fs = require('fs');
const path = require('path');
const {spawn, execFileSync} = require('child_process');

let cdp;
try {
  cdp = require('./cdp.js');
} catch (e) {
  console.log(`SKIP: ${e.message} (scripts/install-deps.sh installs node-ws)`);
  process.exit(77);
}
try {
  execFileSync('sh', ['-c', 'command -v chromium'], {stdio: 'ignore'});
} catch (e) {
  console.log('SKIP: chromium is not installed (scripts/install-deps.sh installs it)');
  process.exit(77);
}

const [lmk, workDir, sharedData = ''] = process.argv.slice(2);
const WIDTH = 1400, HEIGHT = 850;
const children = [];

function check(condition, message) {
  if (!condition) throw new Error(message);
}

const started = Date.now();
function step(text) {
  console.log(`- ${((Date.now() - started) / 1000).toFixed(1)} s: ${text}`);
}

// The scene and the point to click: the carton of the real milk frame, or of a synthetic tabletop.
function chooseScene() {
  const milk = path.join(sharedData, 'pcl', 'milk_cartoon_all_small_clorox.pcd');
  if (sharedData && fs.existsSync(milk)) {
    // milk.pcd is the carton alone, in the same camera frame: the middle of its bounds.
    const info =
        JSON.parse(execFileSync(lmk, ['info', path.join(sharedData, 'pcl', 'milk.pcd'), '--json']));
    const target = info.bounds.min.map((v, i) => (v + info.bounds.max[i]) / 2);
    return {
      scene: milk,
      target,
      flags: [],
      name: 'carton',
      what: 'the carton of the real milk frame'
    };
  }
  const scene = path.join(workDir, 'tabletop.pcd');
  const out = execFileSync(lmk, ['gen', scene, '--seed', '1']).toString();
  // The cup: seen nearly face-on, the carton of this frame is a flat face, which capture refuses.
  const m = out.match(/cup\s+centre\s+(\S+)\s+(\S+)\s+(\S+)/);
  check(m, `lmk gen did not name the cup:\n${out}`);
  return {
    scene,
    target: m.slice(1, 4).map(Number),
    flags: ['--base-frame'],
    name: 'cup',
    what: 'the cup of a synthetic tabletop (../shared/data is absent)'
  };
}

function startServer(scene, landmarks, flags) {
  const child = spawn(
      lmk, ['serve', scene, '--landmarks', landmarks, '--port', '0', '--quiet', ...flags],
      {stdio: ['ignore', 'pipe', 'pipe'], detached: true});
  children.push(child);
  return new Promise((resolve, reject) => {
    let out = '', err = '';
    const timer =
        setTimeout(() => reject(new Error(`lmk serve did not start:\n${out}${err}`)), 60000);
    child.stderr.on('data', (d) => {
      err += d;
    });
    child.on('exit', (code) => reject(new Error(`lmk serve exited (${code}):\n${out}${err}`)));
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/open (http:\/\/\S+)/);  // with its ?token=
      if (m) {
        clearTimeout(timer);
        resolve(m[1]);
      }
    });
  });
}

// Is the screenshot more than a blank page? Decoded by the page itself: the share of the 3D view's
// pixels that differ from its background, and how many colours they take.
async function checkNotBlank(page, png, name) {
  const stats = await page.evaluate(`(async () => {
    const img = new Image();
    img.src = 'data:image/png;base64,${png.toString('base64')}';
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width; c.height = img.height;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const view = document.getElementById('view').getBoundingClientRect();
    const d = g.getImageData(view.left, view.top, view.width, view.height).data;
    const colours = new Set();
    let differing = 0, n = 0;
    for (let i = 0; i < d.length; i += 4 * 5, ++n) {
      colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
      if (Math.abs(d[i] - 0x18) + Math.abs(d[i + 1] - 0x1a) + Math.abs(d[i + 2] - 0x1b) > 24) {
        ++differing;
      }
    }
    return {covered: differing / n, colours: colours.size};
  })()`);
  step(`${name}: ${(100 * stats.covered).toFixed(1)}% of the view drawn, ${stats.colours} colours`);
  check(stats.covered > 0.1 && stats.colours > 50, `${name} is blank: ${JSON.stringify(stats)}`);
}

// Keeps the screenshot as PNG (checked), and as a smaller JPEG for docs/serve.md.
async function saveScreenshot(page, name) {
  const png = await page.screenshot();
  fs.writeFileSync(path.join(workDir, name), png);
  await checkNotBlank(page, png, name);
  const {data} = await page.send('Page.captureScreenshot', {format: 'jpeg', quality: 80});
  fs.writeFileSync(path.join(workDir, name.replace(/\.png$/, '.jpg')), Buffer.from(data, 'base64'));
}

async function main() {
  fs.rmSync(workDir, {recursive: true, force: true});
  fs.mkdirSync(workDir, {recursive: true});
  const landmarks = path.join(workDir, 'landmarks');
  const {scene, target, flags, name, what} = chooseScene();
  step(`scene ${scene}: ${what}, clicked at ${target.map((v) => v.toFixed(3)).join(' ')}`);

  const url = await startServer(scene, landmarks, flags);
  const chrome = await cdp.launchChromium(
      path.join(workDir, 'chromium-profile'), {width: WIDTH, height: HEIGHT});
  children.push(chrome.process);
  const browser = await cdp.Session.connect(chrome.url);
  const page = await cdp.Page.open(browser, WIDTH, HEIGHT);

  // 1. The scene loads.
  await page.send('Page.navigate', {url});
  await page.waitFor('window.lmkReady && window.lmk && window.lmk.sceneId', 'the page');
  await page.evaluate('window.lmkReady.then(() => true)');
  await page.evaluate('new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))');
  await saveScreenshot(page, 'scene.png');

  // 2. A click on the object: the server's first guess of its box.
  const at = await page.evaluate(`lmk.project(${JSON.stringify(target)})`);
  step(`clicking the ${name} at (${at.x.toFixed(0)}, ${at.y.toFixed(0)}) on the page`);
  await page.click(at.x, at.y);
  const box = await page.waitFor('lmk.capture.box', 'the guessed box');
  const inBox = await page.evaluate(`(() => {
    const b = lmk.capture.box, t = ${JSON.stringify(target)};
    const [w, x, y, z] = b.quaternion;
    const d = [t[0] - b.position[0], t[1] - b.position[1], t[2] - b.position[2]];
    // The target in the box frame: the rotation's transpose applied to d.
    const R = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
               [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
               [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]];
    return [0, 1, 2].every((i) =>
        Math.abs(R[0][i] * d[0] + R[1][i] * d[1] + R[2][i] * d[2]) <= b.size[i] / 2);
  })()`);
  check(inBox, `the guessed box ${JSON.stringify(box)} does not hold the ${name}'s centre`);
  step(`guessed box ${box.size.map((v) => v.toFixed(3)).join(' x ')} m holds the ${name}`);

  // 3. Accept the guess: name it, see the verdict, save.
  await page.type('#landmark-name', name);
  await page.clickOn('#check');
  await page.waitFor('!document.getElementById(\'save\').disabled', 'the verdict');
  step(`verdict: ${await page.evaluate('document.getElementById(\'verdict\').textContent')}`);
  await page.clickOn('#save');
  await page.waitFor(
      'document.getElementById(\'status\').textContent.startsWith(\'wrote\')', 'the capture');
  const file = path.join(landmarks, `${name}.lmk`);
  check(fs.existsSync(file), `${file} was not written`);
  step(`${await page.evaluate('document.getElementById(\'status\').textContent')}`);
  await saveScreenshot(page, 'capture.png');

  // 4. Find it.
  await page.clickOn('#find');
  await page.waitFor(
      'lmk.find.last && document.getElementById(\'find-progress\').hidden', 'the search');
  await page.evaluate('new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))');

  // 5. What the page shows, against lmk find on the same files.
  const shown = await page.evaluate(`[...document.querySelectorAll('#matches tr.match')]
      .map((row) => ({landmark: row.dataset.landmark, error: Number(row.dataset.error),
                      text: row.cells[2].textContent, confidence: row.cells[3].textContent}))`);
  const result = await page.evaluate('lmk.find.last.results[0]');
  await saveScreenshot(page, 'find.png');
  const cli = JSON.parse(execFileSync(lmk, ['find', scene, file, '--json', '-', ...flags]));
  step(
      `page: ${shown.length} match(es), errors ${shown.map((m) => m.text).join(', ')}; ` +
      `lmk find: ${cli.matches.length}`);
  check(shown.length > 0, `the page shows no match for the captured ${name}`);
  check(
      shown.length === cli.matches.length,
      `the page shows ${shown.length} matches, lmk find ${cli.matches.length}`);
  cli.matches.forEach((m, i) => {
    check(shown[i].error === m.error, `match ${i + 1}: error ${shown[i].error} != ${m.error}`);
    check(
        shown[i].text === `${(1000 * m.error).toFixed(3)} mm`,
        `match ${i + 1}: the page reads '${shown[i].text}' for ${m.error} m`);
    const probability = m.confidence.probability;
    const confidence = probability === null ? '–' : probability.toFixed(2);
    check(
        shown[i].confidence === confidence,
        `match ${i + 1}: the page reads confidence '${shown[i].confidence}' for ${probability}`);
    const p = result.matches[i].position;
    check(
        p.every((v, k) => Math.abs(v - m.position[k]) < 1e-9),
        `match ${i + 1}: position ${p} != ${m.position}`);
  });
  // 6. The same file uploaded through the page's file input: a new scene, shown in its place.
  const {root} = await page.send('DOM.getDocument');
  const {nodeId} = await page.send('DOM.querySelector', {nodeId: root.nodeId, selector: '#upload'});
  await page.send('DOM.setFileInputFiles', {nodeId, files: [scene]});
  await page.waitFor(
      `lmk.sceneId !== '1' &&
      document.getElementById('status').textContent.includes('click an object')`,
      'the upload');
  const uploaded = await page.evaluate(`[document.getElementById('scene-select').selectedOptions[0]
      .textContent, document.getElementById('scene-info').textContent]`);
  step(`uploaded: ${uploaded[0]}: ${uploaded[1]}`);
  check(uploaded[0] === `${path.basename(scene)} (uploaded)`, `the picker shows ${uploaded[0]}`);
  const finite = JSON.parse(execFileSync(lmk, ['info', scene, '--json'])).finite_points;
  check(uploaded[1].startsWith(`${finite} points`), `the upload shows '${uploaded[1]}'`);
  check(page.errors.length === 0, `the page reported errors: ${page.errors.join('; ')}`);

  // 7. A PbD program (the paper's tool-rack task) planned on one of its scenes: the page's plan
  // and refusal are lmk pbd plan's.
  const task = path.join(workDir, 'task1');
  execFileSync(lmk, ['pbd', 'demo-tasks', '--task', '1', '--save', workDir], {stdio: 'ignore'});
  for (const [scenario, program] of [
           ['scenario1.pcd', 'pick_tool'], ['scenario3.pcd', 'pick_tool']]) {
    const taskUrl =
        await startServer(path.join(task, scenario), task, ['--programs', task, '--base-frame']);
    await page.send('Page.navigate', {url: taskUrl});
    await page.waitFor('window.lmkReady && window.lmk && window.lmk.sceneId', 'the page');
    await page.evaluate(`(() => {
      const s = document.getElementById('program-select');
      s.value = ${JSON.stringify(program)};
      s.dispatchEvent(new Event('change'));
    })()`);
    await page.clickOn('#plan');
    const verdict = await page.waitFor(
        `(() => {
      const t = document.getElementById('plan-result').textContent;
      return /plan valid|refused/.test(t) && t;
    })()`,
        'the plan');
    let cli;
    try {
      cli = JSON.parse(execFileSync(lmk, [
        'pbd', 'plan', path.join(task, `${program}.json`), '--scene', path.join(task, scenario),
        '--json'
      ]));
    } catch (e) {
      cli = JSON.parse(e.stdout);  // a refused plan exits 1, with the plan's JSON
    }
    const refusal = verdict.match(/refused \(([^)]*)\): (.*)$/);
    step(`${program} on ${scenario}: ${refusal ? `refused: ${refusal[2]}` : 'plan valid'}`);
    check(Boolean(refusal) === !cli.valid, `page: ${verdict}; lmk pbd plan valid: ${cli.valid}`);
    if (refusal) {
      check(
          refusal[1] === cli.refusal.kind && refusal[2] === cli.refusal.message,
          `the page's refusal '${refusal[0]}' is not lmk pbd plan's: ${
              JSON.stringify(cli.refusal)}`);
    } else {
      const drawn = await page.evaluate('lmk.viewer.layers.targets.children.length');
      check(
          drawn === cli.steps.reduce((n, st) => n + st.arms.length, 0),
          `${drawn} gripper targets drawn for ${cli.steps.length} steps`);
    }
    await saveScreenshot(page, `program-${path.basename(scenario, '.pcd')}.png`);
  }
  browser.close();
  console.log(
      `PASS: the page's ${shown.length} match(es) equal lmk find's; screenshots in ` + workDir);
}

function stopAll() {
  for (const child of children) {
    try {
      process.kill(-child.pid, 'SIGKILL');  // the process group: chromium's helpers too
    } catch (e) {                           /* already gone */
    }
  }
}

main().then(
    () => {
      stopAll();
      process.exit(0);
    },
    (e) => {
      console.error(`FAIL: ${e.stack || e.message}`);
      stopAll();
      process.exit(1);
    });
