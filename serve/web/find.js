// SPDX-License-Identifier: BSD-3-Clause
// The find panel: landmarks searched in the current scene on the server's worker pool (POST
// /api/find), with progress; matches drawn with their rank and error, their terms on hover, and
// optionally the candidates the search turned down and why.
import {getJSON, runJob} from '/app/api.js';

function formatError(error, unit) {
  return unit === 'sd' ? `${error.toFixed(3)} sd` : `${(1000 * error).toFixed(3)} mm`;
}

/** A match's calibrated confidence, "0.87", or "–" when no calibration applies. */
function formatConfidence(confidence) {
  if (!confidence || confidence.probability === null) return '–';
  return confidence.probability.toFixed(2);
}

/** The competing pose in words: "slide 8.0 cm, 2° away, error 4.100 mm". */
function competitorText(rival, unit) {
  return `${rival.kind} ${(100 * rival.distance).toFixed(1)} cm, ` +
      `${(rival.angle * 180 / Math.PI).toFixed(0)}° away, error ${formatError(rival.error, unit)}`;
}

/** The tooltip's lines on how sure a match is, each ending in a newline. */
function confidenceText(confidence, unit) {
  if (!confidence) return '';
  let text = `confidence ${formatConfidence(confidence)}\n`;
  if (confidence.doubt) text += `doubt: ${confidence.doubt}\n`;
  if (confidence.competitor) text += `competitor: ${competitorText(confidence.competitor, unit)}\n`;
  return text;
}

export class FindPanel {
  constructor(app, info) {
    this.app = app;
    this.last = null;  // the last search's result, as the API gave it
    const method = document.getElementById('method');
    for (const m of info.methods) method.add(new Option(m, m));
    const metric = document.getElementById('metric');
    metric.add(new Option('method\'s own', ''));
    for (const m of info.metrics) metric.add(new Option(m, m));
    document.getElementById('find').addEventListener('click', () => this.find());
  }

  /** Lists the library's landmarks, ticking `select` (a new capture) or keeping the ticks. */
  async loadLandmarks(select) {
    const {landmarks} = await getJSON('/api/landmarks');
    const list = document.getElementById('landmark-list');
    const ticked = new Set([...list.querySelectorAll('input:checked')].map((i) => i.value));
    if (select) ticked.add(select);
    list.replaceChildren();
    if (landmarks.length === 0) list.textContent = 'no landmarks yet: capture one';
    for (const l of landmarks) {
      const label = document.createElement('label');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.value = l.name;
      box.disabled = Boolean(l.error);
      box.checked = ticked.has(l.name) || (ticked.size === 0 && !l.error);
      label.append(box, ` ${l.name} `);
      label.title = l.error || `${l.points} points`;
      if (l.error) label.className = 'bad';
      list.append(label, document.createElement('br'));
    }
    document.getElementById('find').disabled = landmarks.length === 0;
  }

  // The settings' wire form (docs/serve.md, "Settings"): nested by stage, in metres. A threshold
  // that is not a number goes as typed, for the server to refuse with the reason.
  settings() {
    const settings = {method: document.getElementById('method').value, selection: {}};
    const metric = document.getElementById('metric').value;
    if (metric) settings.selection.metric = metric;
    const threshold = document.getElementById('threshold').value.trim();
    if (threshold) {
      settings.selection.threshold = Number.isFinite(Number(threshold)) ? Number(threshold) : threshold;
    }
    return settings;
  }

  async find() {
    const landmarks =
        [...document.querySelectorAll('#landmark-list input:checked')].map((i) => i.value);
    const progress = document.getElementById('find-progress');
    const message = document.getElementById('find-message');
    const button = document.getElementById('find');
    const rejected = document.getElementById('show-rejected').checked;
    progress.hidden = false;
    progress.value = 0;
    button.disabled = true;
    message.className = 'small';
    message.textContent = 'searching…';
    try {
      this.last = await runJob(
          '/api/find', {
            scene: this.app.sceneId,
            landmarks,
            settings: this.settings(),
            rejected,
          },
          (p) => {
            progress.value = p.fraction;
            message.textContent = p.message;
          });
      this.show(this.last);
    } catch (e) {
      message.className = 'small bad';
      message.textContent = e.message;
    } finally {
      progress.hidden = true;
      button.disabled = false;
    }
  }

  show(result) {
    const table = document.getElementById('matches');
    table.replaceChildren();
    const head = table.insertRow();
    for (const h of ['landmark', 'rank', 'error', 'confidence', 'x', 'y', 'z']) {
      head.append(Object.assign(document.createElement('th'), {textContent: h}));
    }
    const boxes = [];
    const lines = [];
    for (const r of result.results) {
      lines.push(
          `${r.landmark}: ${r.matches.length} match${r.matches.length === 1 ? '' : 'es'}` +
          ` (${r.stats.method}, ${r.stats.metric}, ${r.stats.seeds} seeds)` +
          (r.stats.rejections ? `; ${r.stats.rejections}` : ''));
      const rows = r.matches.map((m, i) => ({m, rank: `${i + 1}`, rejected: false}));
      for (const m of r.rejected || []) rows.push({m, rank: '–', rejected: true});
      for (const {m, rank, rejected} of rows) {
        const tooltip = `${r.landmark} ${rejected ? `rejected: ${m.reason}` : `#${rank}`}\n` +
            `error ${formatError(m.error, r.error_unit)}\n` +
            confidenceText(m.confidence, r.error_unit) + this.app.termsText(m);
        const row = table.insertRow();
        row.className = rejected ? 'rejected' : 'match';
        row.dataset.landmark = r.landmark;
        row.dataset.error = m.error;
        row.title = tooltip;
        for (const text
                 of [r.landmark, rank, formatError(m.error, r.error_unit),
                     formatConfidence(m.confidence), ...m.position.map((v) => v.toFixed(3))]) {
          row.insertCell().textContent = text;
        }
        const box = {position: m.position, quaternion: m.quaternion, size: r.box_size};
        boxes.push({
          box,
          rejected,
          tooltip,
          confidence: m.confidence ? m.confidence.probability : null,
          label: `${r.landmark} ${rejected ? '✗' : `#${rank}`} ` +
              formatError(m.error, r.error_unit) +
              (m.confidence && m.confidence.probability !== null ?
                   ` (${formatConfidence(m.confidence)})` :
                   '')
        });
        // The pose that competes with a kept match, drawn as a ghost of its box: where else the
        // landmark would fit almost as well.
        const rival = !rejected && m.confidence && m.confidence.competitor;
        if (rival) {
          boxes.push({
            box: {position: rival.position, quaternion: rival.quaternion, size: r.box_size},
            competitor: true,
            tooltip: `competitor of ${r.landmark} #${rank}: ${competitorText(rival, r.error_unit)}`,
            label: `${r.landmark} #${rank}'s ${rival.kind}`
          });
        }
      }
    }
    document.getElementById('find-message').textContent = lines.join('\n');
    this.app.viewer.showBoxes(boxes);
  }
}
