// SPDX-License-Identifier: BSD-3-Clause
// A small Chrome DevTools Protocol client for the browser test: starts Debian's Chromium headless
// with remote debugging on a free port, and sends commands to one page over the WebSocket (Debian's
// node-ws). Only what the test needs: commands, and waiting for a page condition.
'use strict';
const {spawn} = require('child_process');
const WebSocket = require('ws');

/** Starts Chromium; resolves to {browser, process} once its DevTools endpoint is listening. */
function launchChromium(userDataDir, {width = 1400, height = 850} = {}) {
  const args = [
    '--headless',
    '--no-sandbox',
    '--disable-gpu',
    '--disable-dev-shm-usage',
    // WebGL in software: headless machines have no GPU.
    '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader',
    '--no-first-run',
    '--no-default-browser-check',
    `--window-size=${width},${height}`,
    `--user-data-dir=${userDataDir}`,
    '--remote-debugging-port=0',
    'about:blank',
  ];
  const child = spawn('chromium', args, {stdio: ['ignore', 'ignore', 'pipe'], detached: true});
  return new Promise((resolve, reject) => {
    let stderr = '';
    const timer = setTimeout(() => reject(new Error(`chromium did not start:\n${stderr}`)), 30000);
    child.on('error', (e) => {
      clearTimeout(timer);
      reject(e);
    });
    child.on('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`chromium exited (${code}):\n${stderr}`));
    });
    child.stderr.on('data', (chunk) => {
      stderr += chunk;
      const m = stderr.match(/DevTools listening on (ws:\/\/\S+)/);
      if (m) {
        clearTimeout(timer);
        resolve({url: m[1], process: child});
      }
    });
  });
}

class Session {
  constructor(ws) {
    this.ws = ws;
    this.nextId = 1;
    this.pending = new Map();
    this.listeners = [];
    ws.on('message', (data) => {
      const msg = JSON.parse(data);
      if (msg.id && this.pending.has(msg.id)) {
        const {resolve, reject, method} = this.pending.get(msg.id);
        this.pending.delete(msg.id);
        if (msg.error)
          reject(new Error(`${method}: ${msg.error.message}`));
        else
          resolve(msg.result);
      } else if (msg.method) {
        for (const l of this.listeners) l(msg);
      }
    });
  }

  static async connect(url) {
    const ws = new WebSocket(url, {perMessageDeflate: false, maxPayload: 256 << 20});
    await new Promise((resolve, reject) => {
      ws.once('open', resolve);
      ws.once('error', reject);
    });
    return new Session(ws);
  }

  send(method, params = {}, sessionId = undefined) {
    const id = this.nextId++;
    this.ws.send(JSON.stringify({id, method, params, sessionId}));
    return new Promise((resolve, reject) => this.pending.set(id, {resolve, reject, method}));
  }

  close() {
    this.ws.close();
  }
}

/** A page (tab) of the browser, driven through a flattened target session. */
class Page {
  static async open(browser, width, height) {
    const {targetId} = await browser.send('Target.createTarget', {url: 'about:blank'});
    const {sessionId} = await browser.send('Target.attachToTarget', {targetId, flatten: true});
    const page = new Page(browser, sessionId);
    page.errors = [];
    browser.listeners.push((msg) => {
      if (msg.sessionId !== sessionId) return;
      if (msg.method === 'Runtime.exceptionThrown') {
        page.errors.push(
            msg.params.exceptionDetails.exception?.description || msg.params.exceptionDetails.text);
      } else if (msg.method === 'Runtime.consoleAPICalled' && msg.params.type === 'error') {
        page.errors.push(msg.params.args.map((a) => a.value ?? a.description).join(' '));
      }
    });
    await page.send('Runtime.enable');
    await page.send('Page.enable');
    await page.send(
        'Emulation.setDeviceMetricsOverride', {width, height, deviceScaleFactor: 1, mobile: false});
    return page;
  }

  constructor(browser, sessionId) {
    this.browser = browser;
    this.sessionId = sessionId;
  }

  send(method, params = {}) {
    return this.browser.send(method, params, this.sessionId);
  }

  /** The value of a JavaScript expression in the page (awaited if it is a promise). */
  async evaluate(expression) {
    const r =
        await this.send('Runtime.evaluate', {expression, awaitPromise: true, returnByValue: true});
    if (r.exceptionDetails) {
      throw new Error(
          `in the page: ${expression}: ` +
          (r.exceptionDetails.exception?.description || r.exceptionDetails.text));
    }
    return r.result.value;
  }

  /** Polls `expression` until it is truthy; its value. */
  async waitFor(expression, what, timeoutMs = 60000) {
    const end = Date.now() + timeoutMs;
    for (;;) {
      const value = await this.evaluate(expression);
      if (value) return value;
      if (Date.now() > end) {
        const errors =
            this.errors && this.errors.length ? `; the page: ${this.errors.join('; ')}` : '';
        throw new Error(`timed out waiting for ${what}${errors}`);
      }
      await new Promise((r) => setTimeout(r, 100));
    }
  }

  /** A real mouse click (move, press, release) at page coordinates. */
  async click(x, y) {
    await this.send('Input.dispatchMouseEvent', {type: 'mouseMoved', x, y});
    await this.send(
        'Input.dispatchMouseEvent',
        {type: 'mousePressed', x, y, button: 'left', buttons: 1, clickCount: 1});
    await this.send(
        'Input.dispatchMouseEvent',
        {type: 'mouseReleased', x, y, button: 'left', buttons: 0, clickCount: 1});
  }

  /** Clicks the middle of the element matched by `selector`. */
  async clickOn(selector) {
    const r = await this.evaluate(`(() => {
      const e = document.querySelector(${JSON.stringify(selector)});
      if (!e) return null;
      const b = e.getBoundingClientRect();
      return {x: b.left + b.width / 2, y: b.top + b.height / 2, disabled: e.disabled};
    })()`);
    if (!r) throw new Error(`no element ${selector} on the page`);
    if (r.disabled) throw new Error(`${selector} is disabled`);
    await this.click(r.x, r.y);
  }

  /** Types text into the element matched by `selector`, as a keyboard would. */
  async type(selector, text) {
    await this.clickOn(selector);
    await this.send('Input.insertText', {text});
  }

  async screenshot() {
    const {data} = await this.send('Page.captureScreenshot', {format: 'png'});
    return Buffer.from(data, 'base64');
  }
}

module.exports = {
  launchChromium,
  Session,
  Page
};
