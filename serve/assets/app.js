// The monitor page: reads the JSON API, listens to the event stream and
// sends every control as a console command line (POST /api/command).
'use strict';

const token = new URLSearchParams(location.search).get('token');
const query = token ? '?token=' + encodeURIComponent(token) : '';
const $ = (sel) => document.querySelector(sel);
let status = null;
let block = null;
// The fields of the trend, in the order added.
const trends = [];
const forces = new Map();

async function get(path) {
  const r = await fetch('api/' + path + query);
  if (!r.ok) throw new Error(path + ': ' + r.status);
  return r;
}

async function command(line) {
  const r = await fetch('api/command' + query, {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ command: line }),
  });
  const body = await r.json();
  const out = $('#console-out');
  const lines = ['> ' + line];
  if (!r.ok) lines.push(body.error);
  for (const rep of body.replies || []) lines.push(rep.ok ? rep.reply : 'error[' + rep.code + ']: ' + rep.message);
  for (const f of body.failures || []) lines.push(f);
  out.textContent = (out.textContent + lines.join('\n') + '\n').slice(-20000);
  out.scrollTop = out.scrollHeight;
  return body;
}

function text(el, value) { if (el.textContent !== value) el.textContent = value; }

function renderStatus(s) {
  status = s;
  document.body.classList.toggle('readonly', !s.writes);
  text($('#mode'), s.writes ? 'controls on' : 'read-only');
  text($('#now'), s.now);
  text($('#speed'), s.speed === 'max' ? 'max' : s.speed + '×');
  text($('#scans'), String(s.scans));
  text($('#late'), String(s.late_scans));
  $('#late').classList.toggle('on', s.late_scans > 0);
  const e = s.error;
  text($('#error'), e ? e.number + ' [' + e.code + '] ' + e.block + ': ' + e.message : 'none');
  $('#error').classList.toggle('on', !!e);
  const body = $('#programs tbody');
  const rows = s.programs.map((p) => {
    const tr = document.createElement('tr');
    for (const v of [p.block, p.kind, String(p.task), p.failed ? 'error (' + p.state + ')' : p.state, p.position]) {
      const td = document.createElement('td');
      td.textContent = v;
      tr.appendChild(td);
    }
    tr.children[3].className = p.failed ? 'state-error' : 'state-' + p.state;
    const td = document.createElement('td');
    td.className = 'write';
    for (const [label, verb] of [['start', 'START'], ['suspend', 'SUSPEND'], ['stop', 'PSTOP']]) {
      const b = document.createElement('button');
      b.textContent = label;
      b.onclick = () => command(verb + ' ' + p.block);
      td.appendChild(b);
    }
    tr.appendChild(td);
    return tr;
  });
  body.replaceChildren(...rows);
  for (const p of s.programs) if (p.picture && !pictureOf(p.block)) addPicture(p);
  if (trends.length) drawTrends();
}

function pictureOf(name) {
  return [...document.querySelectorAll('#pictures .picture')].find((d) => d.dataset.block === name);
}

function addPicture(p) {
  const div = document.createElement('div');
  div.className = 'picture';
  div.dataset.block = p.block;
  const h = document.createElement('h3');
  h.textContent = p.block + ' (' + p.kind + ')';
  div.appendChild(h);
  if (p.picture === 'sfc') {
    const c = document.createElement('div');
    c.className = 'controls write';
    for (const verb of ['RESET', 'STOP', 'HOLD', 'RUN']) {
      const b = document.createElement('button');
      b.textContent = verb.toLowerCase();
      b.onclick = () => command(verb + ' ' + p.block);
      c.appendChild(b);
    }
    const hint = document.createElement('span');
    hint.textContent = ' click a step to hold or release it, a transition to force it';
    c.appendChild(hint);
    div.appendChild(c);
  }
  const svg = document.createElement('div');
  svg.className = 'svg';
  svg.addEventListener('click', (ev) => clickPicture(p, ev));
  div.appendChild(svg);
  $('#pictures').appendChild(div);
  loadPicture(p.block);
}

async function loadPicture(name) {
  const r = await get('pictures/' + encodeURIComponent(name));
  setPicture(name, await r.text());
}

// A new drawing replaces the old one node by node where they have the
// same shape, so the elements under the engineer's pointer stay the same
// (a click is not lost to a redraw) and only what changed is touched.
function setPicture(name, svg) {
  const div = pictureOf(name);
  if (!div) return;
  setSvg(div.querySelector('.svg'), svg);
}

function setSvg(host, svg) {
  const tpl = document.createElement('template');
  tpl.innerHTML = svg.trim();
  const fresh = tpl.content.firstElementChild;
  const old = host.firstElementChild;
  if (old && fresh) morph(old, fresh);
  else host.replaceChildren(...tpl.content.childNodes);
}

function morph(a, b) {
  if (a.nodeType !== b.nodeType || a.nodeName !== b.nodeName) { a.replaceWith(b); return; }
  if (a.nodeType === Node.TEXT_NODE) { if (a.nodeValue !== b.nodeValue) a.nodeValue = b.nodeValue; return; }
  if (a.nodeType !== Node.ELEMENT_NODE) return;
  for (const at of [...a.attributes]) if (!b.hasAttribute(at.name)) a.removeAttribute(at.name);
  for (const at of [...b.attributes]) if (a.getAttribute(at.name) !== at.value) a.setAttribute(at.name, at.value);
  const ac = [...a.childNodes];
  const bc = [...b.childNodes];
  if (ac.length !== bc.length) { a.replaceChildren(...bc); return; }
  for (let i = 0; i < ac.length; i++) morph(ac[i], bc[i]);
}

function clickPicture(p, ev) {
  if (!status || !status.writes || p.picture !== 'sfc') return;
  const step = ev.target.closest('g.step');
  if (step) {
    const name = step.id.slice('step-'.length);
    const verb = step.classList.contains('held') ? 'RELEASESTEP' : 'HOLDSTEP';
    command(verb + ' ' + p.block + ' ' + name);
    return;
  }
  const t = ev.target.closest('g.transition');
  if (t) {
    const name = t.id.slice('trans-'.length);
    const key = p.block + '.' + name;
    const next = { NORMAL: 'HOLD', HOLD: 'CONTINUE', CONTINUE: 'NORMAL' }[forces.get(key) || 'NORMAL'];
    forces.set(key, next);
    command('FORCETRANS ' + p.block + ' ' + name + ' ' + next);
  }
}

async function loadBlocks() {
  const list = await (await get('blocks')).json();
  const sel = $('#block-list');
  sel.replaceChildren(...list.map((b) => {
    const o = document.createElement('option');
    o.value = b.name;
    o.textContent = b.name + ' (' + b.type + ')';
    return o;
  }));
  sel.onchange = () => showBlock(sel.value);
  if (list.length) showBlock(list[0].name);
}

async function showBlock(name) {
  const b = await (await get('blocks/' + encodeURIComponent(name))).json();
  block = b.name;
  $('#trend-fields').replaceChildren(...b.fields.map((f) => {
    const o = document.createElement('option');
    o.value = b.name + '.' + f.name;
    return o;
  }));
  $('#fields tbody').replaceChildren(...b.fields.map((f) => {
    const tr = document.createElement('tr');
    const path = b.name + '.' + f.name;
    tr.dataset.path = path;
    const n = document.createElement('td');
    n.textContent = f.name + (f.readonly ? ' (read-only)' : '');
    const v = document.createElement('td');
    v.textContent = f.value;
    v.className = 'value' + (f.forced ? ' forced' : '');
    const c = document.createElement('td');
    c.className = 'write';
    if (!f.readonly) {
      const input = document.createElement('input');
      input.size = 10;
      const mod = document.createElement('button');
      mod.textContent = 'modify';
      mod.onclick = () => command('M ' + path + '=' + input.value).then(() => showBlock(b.name));
      const force = document.createElement('button');
      force.textContent = f.forced ? 'release' : 'force';
      force.onclick = () => command(f.forced ? 'F ' + path + '=N' : 'F ' + path + '=' + input.value).then(() => showBlock(b.name));
      c.append(input, mod, force);
    }
    tr.append(n, v, c);
    return tr;
  }));
}

function values(changed) {
  for (const [path, value] of Object.entries(changed)) {
    if (block && path.startsWith(block + '.')) {
      const tr = [...document.querySelectorAll('#fields tbody tr')].find((r) => r.dataset.path === path);
      if (tr) text(tr.querySelector('.value'), value);
    }
  }
}

// A trend starts with the field's recent past, kept by the server.
async function addTrend(path) {
  if (!path) return;
  const r = await fetch('api/trend/' + encodeURIComponent(path) + query);
  if (!r.ok) { $('#console-out').textContent += 'no field ' + path + '\n'; return; }
  const t = await r.json();
  if (!trends.includes(t.field)) trends.push(t.field);
  drawTrends();
}

// The trend is drawn by the server, by linc-draw as `linc draw` draws a
// trace's trend (time and value axes, strips for BOOLs), and fetched again
// as the plant's clock moves: one request at a time, the latest wins.
let trendBusy = false;
let trendAgain = false;
async function drawTrends() {
  const host = $('#trend');
  if (!trends.length) { host.replaceChildren(); return; }
  if (trendBusy) { trendAgain = true; return; }
  trendBusy = true;
  try {
    const name = 'trend:' + $('#trend-window').value + ':' + trends.join(',');
    const r = await get('pictures/' + encodeURIComponent(name));
    setSvg(host, await r.text());
  } catch (e) {
    $('#console-out').textContent += String(e) + '\n';
  } finally {
    trendBusy = false;
  }
  if (trendAgain) { trendAgain = false; drawTrends(); }
}

function listen() {
  const es = new EventSource('api/events' + query);
  es.addEventListener('status', (e) => renderStatus(JSON.parse(e.data)));
  es.addEventListener('values', (e) => values(JSON.parse(e.data)));
  es.addEventListener('picture', (e) => { const p = JSON.parse(e.data); setPicture(p.block, p.svg); });
  es.addEventListener('resync', () => { start(); });
}

async function start() {
  renderStatus(await (await get('programs')).json());
  for (const div of document.querySelectorAll('#pictures .picture')) loadPicture(div.dataset.block);
  if (block) showBlock(block);
}

$('#console-form').addEventListener('submit', (ev) => {
  ev.preventDefault();
  const line = $('#console-line').value.trim();
  if (line) command(line);
});
$('#trend-form').addEventListener('submit', (ev) => { ev.preventDefault(); addTrend($('#trend-field').value.trim()); });
$('#trend-window').addEventListener('change', () => drawTrends());

start().then(loadBlocks).then(listen).catch((e) => { $('#console-out').textContent = String(e); });
