// SPDX-License-Identifier: BSD-3-Clause
// The programs panel: a PbD program's steps drawn as gripper poses relative to the landmarks
// located in the current scene (POST /api/programs/NAME/plan), and the planner's refusal exactly
// as the robot would give it.
import {getJSON, runJob} from '/app/api.js';

export class ProgramsPanel {
  constructor(app) {
    this.app = app;
    this.select = document.getElementById('program-select');
    document.getElementById('plan').addEventListener('click', () => this.plan());
  }

  async load() {
    const {programs} = await getJSON('/api/programs');
    this.select.replaceChildren();
    for (const p of programs) {
      const text = p.error ? `${p.name} (unreadable)` : `${p.name}: ${p.steps} steps`;
      const option = new Option(text, p.name);
      option.disabled = Boolean(p.error);
      option.title = p.error || `landmarks: ${p.landmarks.join(', ')}`;
      this.select.add(option);
    }
    if (programs.length === 0) this.select.add(new Option('no programs (--programs DIR)', ''));
    document.getElementById('plan').disabled = !programs.some((p) => !p.error);
  }

  async plan() {
    const name = this.select.value;
    const out = document.getElementById('plan-result');
    const progress = document.getElementById('plan-progress');
    progress.hidden = false;
    out.className = 'small';
    out.textContent = `planning '${name}'…`;
    try {
      const result = await runJob(
          `/api/programs/${encodeURIComponent(name)}/plan`,
          {
            scene: this.app.sceneId,
            collisions: document.getElementById('plan-collisions').checked,
          },
          (p) => {
            progress.value = p.fraction;
            out.textContent = p.message;
          });
      this.show(result);
    } catch (e) {
      out.className = 'small bad';
      out.textContent = e.message;
    } finally {
      progress.hidden = true;
    }
  }

  show(result) {
    const {plan, targets, paths} = result;
    const out = document.getElementById('plan-result');
    out.replaceChildren();
    const line = (text, cls = '') => {
      const div = document.createElement('div');
      div.textContent = text;
      div.className = cls;
      out.append(div);
    };
    for (const l of plan.landmarks) {
      line(
          `landmark ${l.name}: at ${l.position.map((v) => v.toFixed(3)).join(', ')}, ` +
          `${l.found} found, ${l.eligible} eligible (${l.policy})`);
    }
    for (const t of targets) {
      line(
          `step ${t.step} ${t.arm} in ${t.frame}: gripper ${t.gripper}` +
          (t.pose ? '' : ' (landmark not located)'));
    }
    // Issue #60: each checked motion's clearance, and where it goes unseen.
    for (const step of plan.steps) {
      for (const arm of step.arms) {
        if (arm.clearance_m === null) continue;
        line(
            `step ${step.step}${step.phase === 'target' ? '' : ` ${step.phase}`} ${arm.arm} ` +
            `motion: clearance ${(100 * arm.clearance_m).toFixed(1)} cm` +
            (arm.planned_around ? ', planned around an obstacle' : '') +
            (arm.unseen.length ? `, ${arm.unseen.length} places no camera has seen` : ''));
      }
    }
    for (const w of plan.warnings) line(`warning: ${w}`);
    if (plan.refusal) {
      line(`refused (${plan.refusal.kind}): ${plan.refusal.message}`, 'bad');
    } else {
      line(`plan valid: ${plan.steps.length} motions`, 'good');
    }
    // The tool frames' swept paths, and what a refused motion would touch.
    const contact = plan.refusal && plan.refusal.contact;
    this.app.viewer.showPaths(
        (paths || []).map((p) => ({points: p.points, around: p.planned_around})),
        contact ? {where: contact.where, label: `${contact.link}: ${contact.obstacle}`} : null);
    const posed = targets.filter((t) => t.pose);
    this.app.viewer.showTargets(posed.map((t) => ({
                                            pose: t.pose,
                                            closed: t.gripper === 'close',
                                            label: `${t.step} ${t.arm}`,
                                          })));
    // Close enough to tell the gripper poses apart.
    this.app.viewer.focus(posed.map((t) => t.pose.position), 1.0);
  }
}
