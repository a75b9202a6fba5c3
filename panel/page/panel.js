// lsc-panel's page: sliders, groups, teach and files over the panel's API
// (lsc-panel.1). No library, nothing from outside this server.
'use strict';

const MOVE_EVERY_MS = 40;     // at most one move per 40 ms while dragging
const TOUCHED_MS = 1500;      // a slider the user moved is not set from read-back meanwhile
const EVENTS_KEPT = 200;

const $ = (sel) => document.querySelector(sel);
let cfg = null;
let kfIds = [];               // the servos of the keyframes
let keyframes = [];           // {time, pos: [..], deg: [..] (null: no joint)} in order
const touched = new Map();    // joint name -> when the user last moved it
const pending = new Map();    // joint name -> value not yet sent
let lastSend = 0;
let timer = null;
let playEnded = true;         // the last play's end has been seen

function say(text, bad) {
  const s = $('#status');
  s.textContent = text;
  s.classList.toggle('bad', !!bad);
}

// A request to the panel; refusals are said in #status and thrown.
async function api(method, path, params, body) {
  const q = new URLSearchParams(params || []).toString();
  const r = await fetch(path + (q ? '?' + q : ''), {
    method, body, headers: body === undefined ? {} : {'Content-Type': 'text/csv'},
    credentials: 'same-origin', cache: 'no-store'});
  const type = r.headers.get('Content-Type') || '';
  const data = type.startsWith('application/json') ? await r.json() : await r.text();
  if (!r.ok) {
    const msg = data && data.error ? data.error : r.status + ' ' + r.statusText;
    say(msg, true);
    throw new Error(msg);
  }
  return data;
}

function el(tag, attrs, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function moveTime() {
  const v = Number($('input[name=time]').value);
  return Number.isInteger(v) && v >= 0 && v <= 65535 ? v : 300;
}

// ---- sliders ------------------------------------------------------------------

function target(j, value) {
  return j.unit === 'deg' ? `${j.name}:${value}deg` : `${j.id}:${value}`;
}

function flush() {
  timer = null;
  if (pending.size === 0) return;
  const params = [['time', String(moveTime())]];
  for (const [name, v] of pending) {
    params.push(['s', target(cfg.joints.find((j) => j.name === name), v)]);
  }
  pending.clear();
  lastSend = performance.now();
  api('POST', '/api/move', params).catch(() => {});
}

function onSlider(j, input) {
  touched.set(j.name, performance.now());
  pending.set(j.name, input.value);
  if (timer !== null) return;                     // the latest value goes when it fires
  const wait = lastSend + MOVE_EVERY_MS - performance.now();
  if (wait <= 0) flush(); else timer = setTimeout(flush, wait);
}

function buildJoints() {
  const box = $('#joints');
  box.textContent = '';
  for (const j of cfg.joints) {
    const row = el('div', {class: 'joint'});
    const id = 'joint-' + j.name;
    row.append(el('label', {for: id}, j.unit === 'deg' ? `${j.name} (${j.id})` : `servo ${j.id}`));
    const input = el('input', {type: 'range', id, name: j.name, min: j.min, max: j.max, step: 1,
      value: j.unit === 'deg' ? Math.min(Math.max(0, j.min), j.max) : 500});
    input.addEventListener('input', () => onSlider(j, input));
    row.append(input);
    row.append(el('output', {for: id, 'data-joint': j.name}, '…'));
    box.append(row);
  }
}

function onPositions(d) {
  document.dispatchEvent(new CustomEvent('lsc-positions', {detail: d}));
  d.ids.forEach((id, i) => {
    const j = cfg.joints.find((x) => x.id === id);
    if (!j) return;
    const deg = d.deg[i];
    const out = document.querySelector(`output[data-joint="${CSS.escape(j.name)}"]`);
    if (out) out.textContent = j.unit === 'deg' && deg !== null ? `${deg}° (${d.pos[i]})` : String(d.pos[i]);
    const t = touched.get(j.name);
    if (t !== undefined && performance.now() - t < TOUCHED_MS) return;
    const input = document.getElementById('joint-' + j.name);
    const v = j.unit === 'deg' ? (deg === null ? null : Math.round(Number(deg))) : d.pos[i];
    if (input && v !== null && document.activeElement !== input) input.value = v;
  });
}

// ---- the servos of a bus (lx:PATH) ------------------------------------------------

const ALARMS = [[1, 'temperature'], [2, 'voltage'], [4, 'stall']];

// GET /api/servos: every servo that answers, with its readings.
async function scan() {
  $('#bus-count').textContent = 'scanning…';
  let d;
  try {
    d = await api('GET', '/api/servos');
  } catch (e) {
    $('#bus-count').textContent = '';
    throw e;
  }
  const body = $('#bus-servos tbody');
  body.textContent = '';
  for (const s of d.servos) {
    const tr = el('tr', {'data-id': String(s.id)});
    tr.append(el('th', {scope: 'row'}, String(s.id)));
    if (s.error) {
      tr.append(el('td', {colspan: '4', class: 'bad'}, s.error));
    } else {
      const alarms = ALARMS.filter(([bit]) => s.alarms & bit).map(([, name]) => name);
      tr.append(el('td', {}, String(s.position)), el('td', {}, `${s.temperature_c} °C`),
        el('td', {}, `${(s.vin_mv / 1000).toFixed(2)} V`),
        el('td', {}, alarms.length ? alarms.join(', ') : 'none'));
    }
    body.append(tr);
  }
  const n = d.servos.length;
  $('#bus-count').textContent = `${n} servo${n === 1 ? '' : 's'} of ${d.asked} ids asked`;
  say(`bus scanned: ${n} servo${n === 1 ? '' : 's'}`);
}

// ---- the hand (a profile with geometry) -------------------------------------------

function onWhere(d) {
  const w = $('#where');
  $('#where-why').textContent = d.error || '';
  for (const k of ['x', 'y', 'z', 'pitch']) {
    if (d.error) delete w.dataset[k]; else w.dataset[k] = String(d[k]);
    $('#where-' + k).textContent = d.error ? '…' : d[k].toFixed(1);
  }
}

// A jog button's name: "x+", "pitch-", ...
async function jog(name) {
  const axis = name.slice(0, -1);
  const sign = name.endsWith('-') ? '-' : '';
  const step = field(axis === 'pitch' ? 'jog-deg' : 'jog-mm').trim();
  const d = await api('POST', '/api/jog', [['axis', axis], ['step', sign + step],
    ['time', String(moveTime())]]);
  say(`to x ${d.x.toFixed(1)} y ${d.y.toFixed(1)} z ${d.z.toFixed(1)} mm, pitch ${d.pitch.toFixed(1)}°`);
}

// ---- events ---------------------------------------------------------------------

const KIND_TEXT = {run: 'started', stop: 'stopped', complete: 'completed',
  'never-started': 'never started: the controller has no such group'};

function onNotification(d) {
  const text = d.kind === 'stop' ? 'action group stopped'
    : d.kind === 'halted' ? 'halted by another program: every servo holds where it is'
    : `group ${d.group} ${KIND_TEXT[d.kind]}` + (d.kind === 'complete' ? ` (${d.times} times)` : '');
  if (d.kind === 'halted') say(text, true);
  if (d.kind === 'never-started') say(text, true);
  const li = el('li', {'data-kind': d.kind, 'data-group': String(d.group)},
    `${new Date().toLocaleTimeString()} ${text}`);
  const list = $('#events');
  list.prepend(li);
  while (list.children.length > EVENTS_KEPT) list.lastElementChild.remove();
}

function onPlay(d) {
  const p = $('#progress');
  p.max = Math.max(1, d.count);
  p.value = d.keyframe;
  document.querySelectorAll('#keyframes li').forEach((li) =>
    li.classList.toggle('current', !d.done && Number(li.dataset.keyframe) === d.keyframe));
  if (d.done) {
    playEnded = true;
    if (d.error) say('play: ' + d.error, true);
    else say(d.stopped ? `play stopped at keyframe ${d.keyframe}` : 'play done');
  }
}

// The controller (or lscd) went away: the panel opens it again by itself.
function onLink(d) {
  const l = $('#link');
  const was = !l.hidden;
  l.hidden = d.up;
  l.textContent = d.up ? '' : 'Reconnecting to the controller… ' + d.message;
  if (d.up && was) say('the controller is back');
}

function listen() {
  const es = new EventSource('/api/events');
  es.addEventListener('battery', (e) => {
    const d = JSON.parse(e.data);
    const b = $('#battery');
    b.textContent = d.mv === null ? 'none' : (d.mv / 1000).toFixed(1) + ' V';
    b.title = d.mv === null ? d.why : '';
  });
  es.addEventListener('positions', (e) => onPositions(JSON.parse(e.data)));
  es.addEventListener('where', (e) => onWhere(JSON.parse(e.data)));
  es.addEventListener('notification', (e) => onNotification(JSON.parse(e.data)));
  es.addEventListener('play', (e) => onPlay(JSON.parse(e.data)));
  es.addEventListener('link', (e) => onLink(JSON.parse(e.data)));
  es.addEventListener('error', (e) => {
    if (e.data) { const d = JSON.parse(e.data); say(`${d.what}: ${d.message}`, true); }
  });
}

// ---- teach ----------------------------------------------------------------------

function csv() {
  return ['time_ms,' + kfIds.join(',')]
    .concat(keyframes.map((k) => [k.time].concat(k.pos).join(','))).join('\n') + '\n';
}

function renderKeyframes() {
  const list = $('#keyframes');
  list.textContent = '';
  keyframes.forEach((k, i) => {
    const n = i + 1;
    const li = el('li', {'data-keyframe': String(n)});
    li.append(el('strong', {}, `#${n}`));
    const time = el('input', {type: 'number', name: 'keyframe-time', min: 0, max: 65535,
      value: k.time, 'aria-label': `time of keyframe ${n} (ms)`, inputmode: 'numeric'});
    time.addEventListener('change', () => {
      const v = Number(time.value);
      if (Number.isInteger(v) && v >= 0 && v <= 65535) k.time = v; else time.value = k.time;
    });
    const label = el('label', {}, 'ms ');
    label.prepend(time);
    li.append(label);
    const act = (name, text, fn, disabled) => {
      const b = el('button', {type: 'button', 'data-action': name, 'aria-label': `${text} keyframe ${n}`}, text);
      b.disabled = !!disabled;
      b.addEventListener('click', fn);
      li.append(b);
    };
    act('go', 'Go to', () => goTo(k));
    act('up', '↑', () => swap(i, i - 1, 'up'), i === 0);
    act('down', '↓', () => swap(i, i + 1, 'down'), i === keyframes.length - 1);
    act('delete', 'Delete', () => { keyframes.splice(i, 1); renderKeyframes(); });
    li.append(el('span', {class: 'pos'}, kfIds.map((id, x) => servoText(id, k, x)).join(', ')));
    list.append(li);
  });
  $('#kf-count').textContent = keyframes.length ? `${keyframes.length} keyframe${keyframes.length > 1 ? 's' : ''}` : '';
}

// A servo of a keyframe as the page speaks of it: "elbow -30.0°" (a joint of
// the arm profile), else "servo 7: 500".
function servoText(id, k, x) {
  const j = cfg.joints.find((q) => q.id === id && q.unit === 'deg');
  const deg = k.deg ? k.deg[x] : null;
  return j && deg !== null && deg !== undefined ? `${j.name} ${Number(deg).toFixed(1)}°`
    : `servo ${id}: ${k.pos[x]}`;
}

function swap(i, j, action) {
  [keyframes[i], keyframes[j]] = [keyframes[j], keyframes[i]];
  renderKeyframes();
  const b = document.querySelector(`#keyframes li[data-keyframe="${j + 1}"] [data-action=${action}]`);
  if (b && !b.disabled) b.focus();
}

async function goTo(k) {
  const params = [['time', String(moveTime())]];
  kfIds.forEach((id, x) => params.push(['s', `${id}:${k.pos[x]}`]));
  await api('POST', '/api/move', params);
  say('moving to the keyframe');
}

async function takePose() {
  const d = await api('POST', '/api/pose');
  if (kfIds.join() !== d.ids.join()) {
    keyframes = [];
    kfIds = d.ids;
  }
  keyframes.push({time: 1000, pos: d.pos, deg: d.deg});
  renderKeyframes();
  say(`keyframe ${keyframes.length} taken`);
}

// ---- files ----------------------------------------------------------------------

async function listFiles() {
  const d = await api('GET', '/api/files');
  const ul = $('#files');
  ul.textContent = '';
  for (const f of d.files) {
    const li = el('li');
    const b = el('button', {type: 'button', 'data-file': f.name}, `Open ${f.name}`);
    b.addEventListener('click', () => openFile(f.name));
    li.append(b, ` ${f.bytes} bytes`);
    ul.append(li);
  }
}

async function openFile(name) {
  const a = await api('GET', '/api/file', [['name', name], ['as', 'json']]);
  kfIds = a.keyframes.length ? a.keyframes[0].servos.ids : [];
  keyframes = a.keyframes.map((k) => ({time: k.time, pos: k.servos.pos, deg: k.servos.deg}));
  renderKeyframes();
  $('input[name=file]').value = name;
  say(`${name}: ${keyframes.length} keyframes`);
}

// ---- buttons --------------------------------------------------------------------

const field = (name) => $(`input[name="${name}"]`).value;

const actions = {
  limp: async () => { await api('POST', '/api/limp'); say('servos limp: pose them by hand'); },
  hold: async () => {
    const d = await api('POST', '/api/hold');
    if (d.beyond && d.beyond.length) say(d.message, true); else say('servos hold');
  },
  halt: async () => {
    const d = await api('POST', '/api/halt');
    if (d.beyond && d.beyond.length) say('halted: ' + d.message, true);
    else say('halted: every servo holds where it is');
  },
  run: async () => { await api('POST', '/api/run', [['group', field('group')], ['times', field('times')]]); },
  stop: async () => { await api('POST', '/api/stop'); },
  speed: async () => {
    await api('POST', '/api/speed', [['group', field('group')], ['percent', field('speed')]]);
    say(`group ${field('group')} at ${field('speed')} %`);
  },
  'take-pose': takePose,
  scan,
  play: async () => {
    if (keyframes.length === 0) { say('take a pose first', true); return; }
    playEnded = false;
    await api('POST', '/api/play', [['speed', field('play-speed')]], csv());
    if (!playEnded) say('playing'); // a short play may have ended already
  },
  'play-stop': async () => { await api('POST', '/api/play-stop'); },
  save: async () => {
    const name = field('file').trim();
    if (keyframes.length === 0) { say('take a pose first', true); return; }
    await api('POST', '/api/save', [['name', name]], csv());
    say(`saved ${name}`);
    await listFiles();
  },
};

async function start() {
  document.querySelectorAll('button[data-action]').forEach((b) => {
    b.addEventListener('click', () => actions[b.dataset.action]().catch(() => {}));
  });
  document.querySelectorAll('button[data-jog]').forEach((b) => {
    b.addEventListener('click', () => jog(b.dataset.jog).catch(() => {}));
  });
  $('input[name=file]').addEventListener('keydown', (e) => {
    if (e.key === 'Enter') actions.save().catch(() => {});
  });
  // Esc halts, wherever the focus is
  document.addEventListener('keydown', (e) => {
    if (e.key === 'Escape') { e.preventDefault(); actions.halt().catch(() => {}); }
  });
  cfg = await api('GET', '/api/config');
  $('#device').textContent = `${cfg.name} (${cfg.kind})`;
  $('#dir').textContent = cfg.dir;
  $('#groups').textContent = cfg.groups.length ? 'groups here: ' + cfg.groups.join(', ') : '';
  buildJoints();
  $('#hand').hidden = !cfg.geometry;
  $('#bus').hidden = cfg.kind !== 'lx'; // a bus of servos opened directly
  document.dispatchEvent(new CustomEvent('lsc-config', {detail: cfg}));
  listen();
  await listFiles();
}

start().catch((e) => say(String(e.message || e), true));
