// lsc-panel's Calibrate section (docs/arm-profile.md, "Calibration"): the
// four poses, each drawn, taken with /api/calibrate; and a live drawing of the
// arm, a side and a top view from the joints' angles and the profile's
// lengths (the forward kinematics of docs/kinematics.md), the grasp point
// marked, so that an owner sees at once when the picture and the arm
// disagree. Uses panel.js's api(), say() and el(); panel.js tells it the
// configuration and the positions (events 'lsc-config', 'lsc-positions').
'use strict';

const SVG = 'http://www.w3.org/2000/svg';
const CAL_STEPS = [
  {step: 'home', text: 'Hold the arm straight up, every joint at 0°: the base facing +x, ' +
    'upper arm, forearm and hand in one vertical line, the wrist roll at its middle.',
   pose: [0, 0, 0, 0]},
  {step: 'lean', text: 'Lean every joint its positive way by 20° or more: shoulder, elbow ' +
    'and wrist forward (toward +x), the base toward +y, the wrist roll its positive way.',
   pose: [25, 25, 25, 25]},
  {step: 'gripper-closed', text: 'Close the gripper.', pose: null},
  {step: 'gripper-open', text: 'Open the gripper.', pose: null},
];
let calCfg = null;

function svgEl(tag, attrs) {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  return e;
}

// The chain's points for the angles q = [base, shoulder, elbow, wrist] (degrees):
// {side: [[r, z]...], top: [[x, y]...], tip: {x, y, z}} in mm.
function armPoints(q, links) {
  const rad = Math.PI / 180;
  const [b, s, e, w] = q.map((v) => v * rad);
  let r = 0;
  let z = links.height;
  const side = [[0, 0], [0, z]];
  for (const [len, a] of [[links.upper, s], [links.fore, s + e], [links.tool, s + e + w]]) {
    r += len * Math.sin(a);
    z += len * Math.cos(a);
    side.push([r, z]);
  }
  const top = side.slice(1).map(([rr]) => [rr * Math.cos(b), rr * Math.sin(b)]);
  return {side, top, tip: {x: r * Math.cos(b), y: r * Math.sin(b), z}};
}

// Draws the arm at angles q into svg (its two views side by side); the grasp
// point's circle carries its coordinates (data-x, data-y, data-z, mm).
function drawArm(svg, q, links) {
  const reach = links.height + links.upper + links.fore + links.tool;
  const p = armPoints(q, links);
  svg.replaceChildren();
  svg.setAttribute('viewBox', `${-reach} ${-reach} ${4 * reach + 40} ${reach + 20}`);
  const side = svgEl('g', {class: 'side'});
  const top = svgEl('g', {class: 'top', transform: `translate(${2 * reach + 40} ${-reach / 2})`});
  side.append(svgEl('line', {x1: -reach, y1: 0, x2: reach, y2: 0, class: 'table'}));
  top.append(svgEl('circle', {cx: 0, cy: 0, r: 6, class: 'table'}));
  side.append(svgEl('polyline', {points: p.side.map(([r, z]) => `${r},${-z}`).join(' '),
    class: 'arm'}));
  top.append(svgEl('polyline', {points: [[0, 0], ...p.top].map(([x, y]) => `${x},${-y}`).join(' '),
    class: 'arm'}));
  for (const [g, cx, cy] of [[side, p.side[4][0], -p.tip.z], [top, p.tip.x, -p.tip.y]]) {
    g.append(svgEl('circle', {cx, cy, r: 8, class: 'tip', 'data-x': p.tip.x.toFixed(2),
      'data-y': p.tip.y.toFixed(2), 'data-z': p.tip.z.toFixed(2)}));
  }
  const label = (g, text) => g.append(Object.assign(svgEl('text', {x: -reach, y: -reach + 24}),
    {textContent: text}));
  label(side, 'side');
  label(top, 'top');
  svg.append(side, top);
}

function showState(d) {
  const t = document.getElementById('cal-state');
  t.replaceChildren(el('tr', {}, ''));
  t.firstChild.append(el('th', {}, 'joint'), el('th', {}, 'offset'), el('th', {}, 'dir'),
    el('th', {}, 'open / closed'));
  for (const j of d.joints) {
    const tr = el('tr', {'data-joint': j.name});
    const ends = j.open !== undefined || j.closed !== undefined
      ? `${j.open ?? '…'} / ${j.closed ?? '…'}` : '';
    tr.append(el('td', {}, j.name), el('td', {}, (j.offset > 0 ? '+' : '') + j.offset),
      el('td', {}, j.dir > 0 ? '+1' : '-1'), el('td', {}, ends));
    t.append(tr);
  }
}

async function calibrate(step) {
  const d = await api('POST', '/api/calibrate', [['step', step]]);
  if (step === 'save') {
    say(`calibration written to ${d.written}: start lsc-panel without --arm to use it`);
    document.getElementById('cal-state').replaceChildren();
    document.querySelectorAll('#cal-steps li').forEach((li) => li.classList.remove('done'));
  } else if (step === 'cancel') {
    say('calibration cancelled: nothing written');
    document.getElementById('cal-state').replaceChildren();
    document.querySelectorAll('#cal-steps li').forEach((li) => li.classList.remove('done'));
  } else {
    showState(d);
    document.querySelector(`#cal-steps li[data-step="${step}"]`).classList.add('done');
    say(`${step} taken`);
  }
}

function buildSteps() {
  const list = document.getElementById('cal-steps');
  list.replaceChildren();
  for (const s of CAL_STEPS) {
    const li = el('li', {'data-step': s.step});
    li.append(el('p', {}, s.text));
    if (s.pose !== null) {
      const svg = svgEl('svg', {class: 'pose', role: 'img', 'aria-label': `the pose: ${s.step}`});
      drawArm(svg, s.pose, calCfg.links);
      li.append(svg);
    }
    const b = el('button', {type: 'button', 'data-cal': s.step}, 'Take');
    b.addEventListener('click', () => calibrate(s.step).catch(() => {}));
    li.append(b);
    list.append(li);
  }
}

document.addEventListener('lsc-config', (e) => {
  calCfg = e.detail;
  const section = document.getElementById('calibrate');
  section.hidden = !calCfg.geometry || !calCfg.links;
  if (section.hidden) return;
  document.getElementById('cal-out').textContent = calCfg.calibrate_out
    ? `The result goes to ${calCfg.calibrate_out}.`
    : 'This controller has no name to keep a profile under: calibrate with lscctl calibrate --out FILE.';
  document.getElementById('cal-profile').textContent = calCfg.profile
    ? `Arm profile: ${calCfg.profile}${calCfg.calibrated ? ' (calibrated for this arm)' : ''}.` : '';
  buildSteps();
  for (const a of ['save', 'cancel']) {
    document.querySelector(`button[data-cal="${a}"]`).addEventListener('click',
      () => calibrate(a).catch(() => {}));
  }
});

document.addEventListener('lsc-positions', (e) => {
  if (!calCfg || !calCfg.links) return;
  const d = e.detail;
  const q = calCfg.chain.slice(0, 4).map((id) => {
    const i = d.ids.indexOf(id);
    return i < 0 || d.deg[i] === null ? null : Number(d.deg[i]);
  });
  if (q.some((v) => v === null)) return;
  drawArm(document.getElementById('cal-arm'), q, calCfg.links);
});
