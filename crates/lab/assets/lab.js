// gonio lab: the page. It holds the formulation (the coating description's tables as JSON,
// docs/coatings.md), builds the form from it, and asks the server (docs/lab.md) for readings and
// pictures whenever it changes. Every number shown comes from the server; the page computes
// nothing but the layout of its plots.
'use strict';

const $ = (id) => document.getElementById(id);
const el = (tag, attrs = {}, ...children) => {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else if (v !== undefined && v !== null) e.setAttribute(k, v);
  }
  for (const c of children) if (c !== null && c !== undefined) e.append(c);
  return e;
};
const fmt = (x, digits = 1) => (x === null || x === undefined || Number.isNaN(x)) ? '–' : Number(x).toFixed(digits);

const state = {
  f: null,            // the formulation (B, current)
  readings: null,     // its readings
  target: null,       // {id, name, read}
  pinned: null,       // {f, readings, picture (object URL)}
  topography: null,   // {id, name, read}: the uploaded map the formulation names
  pigments: [],
  invalid: null,      // the server's message when the formulation is refused
};

// ---------------------------------------------------------------- the server

async function api(path, body, { signal, blob } = {}) {
  const init = body === undefined ? {} : {
    method: 'POST',
    headers: { 'content-type': body instanceof Blob ? 'application/octet-stream' : 'application/json' },
    body: body instanceof Blob ? body : JSON.stringify(body),
  };
  const r = await fetch(path, { ...init, signal });
  if (!r.ok) {
    let message = r.statusText;
    try { message = (await r.json()).error; } catch (_) { /* not JSON */ }
    const e = new Error(message);
    e.status = r.status;
    throw e;
  }
  return blob ? r : r.json();
}

// A computation that follows the formulation: at most one request in flight; a change while it
// runs marks it stale and the newest formulation is sent as soon as it returns, so a dragged
// slider shows results as it moves and never queues requests. `abort()` stops it (the server
// then cancels the computation).
function follower(run) {
  let controller = null;
  let stale = false;
  const go = async () => {
    if (controller) { stale = true; return; }
    stale = false;
    controller = new AbortController();
    try {
      await run(controller.signal, () => stale);
    } catch (e) {
      if (e.name !== 'AbortError' && e.status !== 409) showError(e.message);
    } finally {
      controller = null;
      if (stale) go();
    }
  };
  return { go, abort() { stale = false; if (controller) controller.abort(); }, busy: () => controller !== null };
}

function showError(message) {
  const box = $('message');
  box.textContent = message;
  box.hidden = !message;
}

function setState(id, text, cls = '') {
  const s = $(id);
  s.textContent = text;
  s.className = 'state ' + cls;
}

// ---------------------------------------------------------------- formulation ↔ URL

function encode(f) {
  const bytes = new TextEncoder().encode(JSON.stringify(f));
  let s = '';
  for (const b of bytes) s += String.fromCharCode(b);
  return btoa(s).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function decode(text) {
  const s = atob(text.replace(/-/g, '+').replace(/_/g, '/'));
  return JSON.parse(new TextDecoder().decode(Uint8Array.from(s, (c) => c.charCodeAt(0))));
}

function saveToUrl() {
  history.replaceState(null, '', '#f=' + encode(state.f));
}

// ---------------------------------------------------------------- the form

const get = (path) => path.reduce((o, k) => (o == null ? undefined : o[k]), state.f);
function set(path, value) {
  let o = state.f;
  for (const k of path.slice(0, -1)) {
    if (o[k] === undefined || o[k] === null || typeof o[k] !== 'object') o[k] = {};
    o = o[k];
  }
  if (value === undefined) delete o[path[path.length - 1]];
  else o[path[path.length - 1]] = value;
}

// A number with a slider: `log` sliders move on a logarithmic scale. The number field takes any
// value; the server's checks (the coating library's) say what is wrong with it.
function slider(parent, { path, label, unit = '', min, max, step = 'any', log = false, title }) {
  const value = get(path);
  const toRange = (v) => log ? 1000 * Math.log(v / min) / Math.log(max / min) : v;
  const fromRange = (r) => log ? min * Math.pow(max / min, r / 1000) : Number(r);
  const range = el('input', {
    type: 'range', min: log ? 0 : min, max: log ? 1000 : max, step: log ? 1 : step,
    'aria-label': label, 'data-path': path.join('.'),
  });
  range.value = toRange(value);
  const number = el('input', { type: 'number', step: 'any', 'aria-label': label + ' (' + unit + ')', 'data-path': path.join('.') });
  number.value = round(value);
  range.addEventListener('input', () => {
    const v = round(fromRange(Number(range.value)));
    number.value = v;
    set(path, v);
    changed();
  });
  number.addEventListener('change', () => {
    const v = Number(number.value);
    if (number.value === '' || !Number.isFinite(v)) return;
    range.value = toRange(Math.min(Math.max(v, min), max));
    set(path, v);
    changed();
  });
  parent.append(el('div', { class: 'row', 'data-path': path.join('.'), title: title || '' },
    el('label', {}, label), range, number, el('span', { class: 'unit' }, unit)));
}

// Three significant digits, as a number.
function round(v) {
  if (!Number.isFinite(v) || v === 0) return v;
  const digits = Math.max(0, 2 - Math.floor(Math.log10(Math.abs(v))));
  return Number(v.toFixed(Math.min(digits, 6)));
}

function choice(parent, { label, options, value, onchange, title }) {
  const select = el('select', { 'aria-label': label, title: title || '' },
    ...options.map(([v, text]) => el('option', { value: v }, text)));
  select.value = value;
  select.addEventListener('change', () => { onchange(select.value); buildForm(); changed(); });
  parent.append(el('div', { class: 'row choice' }, el('label', {}, label), select));
}

function note(parent, text) { parent.append(el('div', { class: 'note' }, text)); }

// A spectrum field: a constant (a slider) or a sampled spectrum {nm, values}, edited as lines
// of "wavelength value".
function spectrum(parent, { path, label, unit = '', min, max, log = false, fallback }) {
  const value = get(path);
  const sampled = value !== null && typeof value === 'object';
  choice(parent, {
    label, value: sampled ? 'spectrum' : 'constant',
    options: [['constant', 'constant over λ'], ['spectrum', 'spectrum (nm, value)']],
    onchange: (v) => {
      if (v === 'constant') set(path, sampled ? round(mean(value.values)) : (value ?? fallback));
      else set(path, { nm: [400, 550, 700], values: [value ?? fallback, value ?? fallback, value ?? fallback] });
    },
  });
  if (!sampled) {
    slider(parent, { path, label: '', unit, min, max, log });
    return;
  }
  const text = el('textarea', { rows: 4, 'aria-label': label + ' spectrum', 'data-path': path.join('.') });
  text.value = value.nm.map((w, i) => `${w} ${value.values[i]}`).join('\n');
  text.addEventListener('change', () => {
    const rows = text.value.trim().split(/\n+/).map((l) => l.trim().split(/[\s,;]+/).map(Number));
    if (rows.some((r) => r.length !== 2 || r.some((x) => !Number.isFinite(x)))) {
      showError(`${label}: each line is a wavelength in nm and a value`);
      return;
    }
    set(path, { nm: rows.map((r) => r[0]), values: rows.map((r) => r[1]) });
    changed();
  });
  parent.append(el('details', { class: 'spectrum' },
    el('summary', {}, `${value.nm.length} points, ${Math.min(...value.nm)}–${Math.max(...value.nm)} nm, mean ${fmt(mean(value.values), 3)} ${unit}`),
    text));
}

const mean = (v) => v.reduce((a, b) => a + b, 0) / v.length;

function buildForm() {
  const form = $('form');
  form.replaceChildren();
  const f = state.f;

  // The top interface.
  const top = el('fieldset', {}, el('legend', {}, 'Top surface of the clear coat'));
  const r = f.top?.roughness;
  const mode = !r ? 'smooth' : r.map ? 'map' : r.sq_um !== undefined ? 'sq' : (r.distribution === 'beckmann' ? 'beckmann' : 'ggx');
  choice(top, {
    label: 'surface', value: mode,
    title: 'how the top interface between air and the clear coat is rough',
    options: [['smooth', 'smooth (a mirror)'], ['ggx', 'rough: GGX, α'], ['beckmann', 'rough: Beckmann, α'],
      ['sq', 'rough: Sq and T (Beckmann)'], ['map', 'rough: a measured topography']],
    onchange: (v) => {
      const alpha = r?.alpha ?? 0.05;
      if (v === 'smooth') delete f.top;
      else if (v === 'ggx' || v === 'beckmann') f.top = { roughness: { distribution: v, alpha } };
      else if (v === 'sq') f.top = { roughness: { distribution: 'beckmann', sq_um: 0.1, correlation_um: 5 } };
      else if (state.topography) f.top = { roughness: { map: state.topography.id } };
      else { f.top = { roughness: { distribution: 'ggx', alpha } }; $('form').dataset.wantMap = '1'; }
    },
  });
  if (mode === 'ggx' || mode === 'beckmann') {
    slider(top, { path: ['top', 'roughness', 'alpha'], label: 'roughness α', unit: '', min: 0.002, max: 0.5, log: true,
      title: 'the microfacet roughness (≈ rms slope); gloss falls as it grows' });
  } else if (mode === 'sq') {
    slider(top, { path: ['top', 'roughness', 'sq_um'], label: 'Sq', unit: 'µm', min: 0.005, max: 2, log: true });
    slider(top, { path: ['top', 'roughness', 'correlation_um'], label: 'correlation T', unit: 'µm', min: 0.5, max: 200, log: true });
    note(top, `rms slope 2 Sq/T = ${fmt(2 * r.sq_um / r.correlation_um, 4)}`);
  }
  if (mode === 'map' || $('form').dataset.wantMap) {
    delete $('form').dataset.wantMap;
    const input = el('input', { type: 'file', id: 'open-topography', 'aria-label': 'topography file' });
    input.addEventListener('change', () => uploadTopography(input.files[0]));
    top.append(el('div', { class: 'row choice' }, el('label', {}, 'topography'), input));
    if (state.topography && mode === 'map') {
      const s = state.topography.read;
      top.append(el('div', { class: 'stats', id: 'topography-stats' },
        `${state.topography.name}: ${s.nx} × ${s.ny} points at ${fmt(s.dx_um, 3)} × ${fmt(s.dy_um, 3)} µm; ` +
        `Sq ${fmt(s.sq_um, 4)} µm, Sa ${fmt(s.sa_um, 4)} µm, Ssk ${fmt(s.ssk, 2)}, Sku ${fmt(s.sku, 2)}, ` +
        `rms slope Sdq ${fmt(s.sdq, 4)}` + (s.sal_um ? `, Sal ${fmt(s.sal_um, 2)} µm` : '')));
      note(top, 'The top is Beckmann with the map\'s rms slope Sdq (docs/coatings.md).');
    } else if (mode === 'map') {
      note(top, `map ${r.map}: upload the file again (uploads last while the lab runs)`);
    } else {
      note(top, 'Choose an instrument file (any format gonio reads: .sdf, .x3p, .datx, .plu, .gwy …).');
    }
  }
  form.append(top);

  // The clear coat.
  const coat = el('fieldset', {}, el('legend', {}, 'Clear coat'));
  const index = f.coat.index;
  const imode = typeof index === 'number' ? 'constant' : index.cauchy_a !== undefined ? 'cauchy'
    : index.sellmeier_b !== undefined ? 'sellmeier' : 'measured';
  choice(coat, {
    label: 'refractive index', value: imode,
    options: [['constant', 'constant'], ['cauchy', 'Cauchy a + b/λ²'], ['sellmeier', 'Sellmeier'], ['measured', 'measured (nm, n)']],
    onchange: (v) => {
      const n = typeof index === 'number' ? index : 1.5;
      f.coat.index = v === 'constant' ? n : v === 'cauchy' ? { cauchy_a: 1.48, cauchy_b_um2: 0.0045 }
        : v === 'sellmeier' ? { sellmeier_b: [1.03961212, 0.231792344, 1.01046945], sellmeier_c_um2: [0.00600069867, 0.0200179144, 103.560653] }
          : { nm: [400, 550, 700], values: [n, n, n] };
    },
  });
  if (imode === 'constant') slider(coat, { path: ['coat', 'index'], label: 'n', min: 1.3, max: 1.9, step: 0.001 });
  if (imode === 'cauchy') {
    slider(coat, { path: ['coat', 'index', 'cauchy_a'], label: 'Cauchy a', min: 1.3, max: 1.8, step: 0.001 });
    slider(coat, { path: ['coat', 'index', 'cauchy_b_um2'], label: 'Cauchy b', unit: 'µm²', min: 0, max: 0.03, step: 0.0001 });
  }
  if (imode === 'sellmeier') {
    for (let i = 0; i < 3; i++) {
      slider(coat, { path: ['coat', 'index', 'sellmeier_b', i], label: `B${i + 1}`, min: 0, max: 3, step: 0.001 });
      slider(coat, { path: ['coat', 'index', 'sellmeier_c_um2', i], label: `C${i + 1}`, unit: 'µm²', min: 0, max: 200, step: 0.0001 });
    }
  }
  if (imode === 'measured') spectrum(coat, { path: ['coat', 'index'], label: 'n(λ)', min: 1.3, max: 1.9, fallback: 1.5 });
  slider(coat, { path: ['coat', 'thickness_um'], label: 'thickness', unit: 'µm', min: 1, max: 200, step: 1 });
  if (f.coat.absorption_per_um === undefined) f.coat.absorption_per_um = 0;
  spectrum(coat, { path: ['coat', 'absorption_per_um'], label: 'absorption σ', unit: '1/µm', min: 0, max: 0.05, fallback: 0 });
  form.append(coat);

  // The flakes.
  const flakes = el('fieldset', {}, el('legend', {}, 'Effect flakes'));
  const fl = f.flakes;
  choice(flakes, {
    label: 'flakes', value: fl ? fl.kind : 'none',
    options: [['none', 'none (a solid colour)'], ['aluminium', 'aluminium'], ['metal', 'metal (n, k)'], ['interference', 'interference (TiO₂ on mica)']],
    onchange: (v) => {
      const keep = { coverage: fl?.coverage ?? 0.5, tilt_deg: fl?.tilt_deg ?? 12 };
      if (v === 'none') delete f.flakes;
      else if (v === 'aluminium') f.flakes = { kind: v, ...keep };
      else if (v === 'metal') f.flakes = { kind: v, ...keep, n: 1.2, k: 7 };
      else f.flakes = { kind: v, ...keep, tio2_nm: 120, mica_nm: 300, mica_index: 1.58 };
    },
  });
  if (fl) {
    slider(flakes, { path: ['flakes', 'coverage'], label: 'coverage', unit: '', min: 0, max: 1, step: 0.01, title: 'fraction of the base the flakes cover' });
    slider(flakes, { path: ['flakes', 'tilt_deg'], label: 'tilt spread', unit: '°', min: 0.5, max: 45, step: 0.1, title: 'rms tilt of the flakes from the coating plane' });
    if (fl.kind === 'metal') {
      spectrum(flakes, { path: ['flakes', 'n'], label: 'metal n', min: 0.05, max: 5, fallback: 1 });
      spectrum(flakes, { path: ['flakes', 'k'], label: 'metal k', min: 0, max: 10, fallback: 5 });
    }
    if (fl.kind === 'interference') {
      slider(flakes, { path: ['flakes', 'tio2_nm'], label: 'TiO₂ layer', unit: 'nm', min: 20, max: 400, step: 1 });
      slider(flakes, { path: ['flakes', 'mica_nm'], label: 'mica', unit: 'nm', min: 50, max: 1000, step: 1 });
      slider(flakes, { path: ['flakes', 'mica_index'], label: 'mica index', unit: '', min: 1.4, max: 1.8, step: 0.01 });
    }
  }
  form.append(flakes);

  // The base.
  const base = el('fieldset', {}, el('legend', {}, 'Base (basecoat under the flakes)'));
  choice(base, {
    label: 'base', value: f.base.kind,
    options: [['diffuse', 'diffuse reflectance'], ['kubelka-munk', 'pigments (Kubelka-Munk)']],
    onchange: (v) => {
      if (v === 'diffuse') f.base = { kind: v, reflectance: 0.25 };
      else f.base = { kind: v, thickness_um: 20, substrate: 0.8, pigment: state.pigments.slice(0, 1).map((p) => ({ ...p.pigment })) };
    },
  });
  if (f.base.kind === 'diffuse') {
    spectrum(base, { path: ['base', 'reflectance'], label: 'reflectance', min: 0, max: 1, fallback: 0.25 });
  } else {
    slider(base, { path: ['base', 'thickness_um'], label: 'thickness', unit: 'µm', min: 1, max: 100, step: 0.5 });
    spectrum(base, { path: ['base', 'substrate'], label: 'substrate', min: 0, max: 1, fallback: 0.8 });
    (f.base.pigment || []).forEach((p, i) => {
      const box = el('div', { class: 'pigment' },
        el('div', {}, el('span', { class: 'name' }, p.name ?? p.library), ' ',
          el('button', { type: 'button', title: 'remove this pigment', onclick: () => { f.base.pigment.splice(i, 1); buildForm(); changed(); } }, 'remove')));
      slider(box, { path: ['base', 'pigment', i, 'concentration'], label: 'concentration', unit: '', min: 0.001, max: 10, log: true,
        title: 'multiplies the pigment\'s K and S (per µm)' });
      base.append(box);
    });
    const names = new Set((f.base.pigment || []).map((p) => p.name ?? p.library));
    const offer = state.pigments.filter((p) => !names.has(p.name));
    if (offer.length) {
      const add = el('select', { 'aria-label': 'add a pigment' }, el('option', { value: '' }, 'add a pigment…'),
        ...offer.map((p) => el('option', { value: p.name }, p.library ? `${p.name} (library, ${p.colour_index})` : `${p.name} (from ${p.example})`)));
      add.addEventListener('change', () => {
        const p = state.pigments.find((q) => q.name === add.value);
        if (!p) return;
        f.base.pigment = [...(f.base.pigment || []), { ...p.pigment }];
        buildForm();
        changed();
      });
      base.append(el('div', { class: 'row choice' }, el('label', {}, ''), add));
    }
  }
  form.append(base);
  markInvalid();
}

// Show the server's message beside the field it names. The coating library names a field by its
// table and its name without the unit ("coat thickness -4 µm", "flake coverage 1.5"): the row
// whose last key (less its unit suffix) is in the message, preferring one of the table named.
function markInvalid() {
  document.querySelectorAll('.field-error').forEach((e) => e.remove());
  document.querySelectorAll('.row.invalid').forEach((e) => e.classList.remove('invalid'));
  if (!state.invalid) return;
  const message = state.invalid.toLowerCase();
  let best = null;
  let bestScore = 1;
  document.querySelectorAll('.row[data-path]').forEach((row) => {
    const keys = row.dataset.path.split('.').filter((k) => !/^\d+$/.test(k));
    const field = keys[keys.length - 1].replace(/_(um|nm|deg|per_um|um2)$/, '').replace(/_/g, ' ');
    const table = keys[0].replace(/s$/, '');
    const score = (message.includes(field) ? 2 : 0) + (message.includes(table) ? 1 : 0);
    if (score > bestScore) { best = row; bestScore = score; }
  });
  if (best) {
    best.classList.add('invalid');
    best.after(el('div', { class: 'field-error' }, state.invalid));
  }
}

// ---------------------------------------------------------------- computations

const readings = follower(async (signal) => {
  setState('readings-state', 'computing…', 'busy');
  const body = { formulation: state.f, standard: $('standard').value, incidence_deg: Number($('incidence').value), channel: 'readings-B' };
  if (state.target) body.target = state.target.id;
  try {
    const r = await api('/api/readings', body, { signal });
    state.readings = r;
    state.invalid = null;
    showError('');
    markInvalid();
    $('form-state').textContent = '';
    setState('readings-state', `${Math.round(r.seconds * 1000)} ms`);
    showReadings();
  } catch (e) {
    if (e.status === 400) {
      state.invalid = e.message;
      markInvalid();
      setState('form-state', 'not valid: ' + e.message, 'error');
      setState('readings-state', 'formulation not valid', 'error');
      return;
    }
    throw e;
  }
});

let pictureUrl = null;
const picture = follower(async (signal, stale) => {
  converged.abort();
  setState('picture-state', 'preview…', 'busy');
  const ok = await renderInto('preview', signal);
  if (ok && !stale()) converged.go();
});
// While nothing changes the picture refines: the converged table at few samples, then the
// finished picture (docs/render.md, "Panel pictures"); a change aborts it.
const converged = follower(async (signal) => {
  setState('picture-state', 'refining…', 'busy');
  if (!(await renderInto('refined', signal))) return;
  setState('picture-state', 'converging…', 'busy');
  await renderInto('converged', signal);
});

async function renderInto(quality, signal) {
  const t0 = performance.now();
  let r;
  try {
    r = await api('/api/picture', { formulation: state.f, lighting: $('lighting').value, quality, channel: 'picture-B' }, { signal, blob: true });
  } catch (e) {
    if (e.status === 400) { setState('picture-state', 'formulation not valid', 'error'); return false; }
    throw e;
  }
  const blob = await r.blob();
  if (pictureUrl) URL.revokeObjectURL(pictureUrl);
  pictureUrl = URL.createObjectURL(blob);
  $('picture').src = pictureUrl;
  const spp = r.headers.get('x-gonio-spp');
  const size = r.headers.get('x-gonio-size');
  $('picture').title = `${quality}: ${size} pixels, ${spp} samples per pixel; table ${r.headers.get('x-gonio-table')}`;
  setState('picture-state', `${quality} · ${((performance.now() - t0) / 1000).toFixed(1)} s · ${size}`);
  $('picture').dataset.quality = quality;
  return true;
}

function changed() {
  saveToUrl();
  readings.go();
  picture.go();
  constituentsSoon();
}

// ---------------------------------------------------------------- showing the readings

function showReadings() {
  const b = state.readings;
  const a = state.pinned?.readings;
  const rows = [];
  const row = (label, unit, pick, digits = 1, tip = '') => {
    const vb = b ? pick(b) : null;
    const va = a ? pick(a) : null;
    rows.push(el('tr', { title: tip }, el('td', {}, label),
      ...(a ? [el('td', { class: 'a' }, typeof va === 'string' ? va : fmt(va, digits))] : []),
      el('td', { class: 'b' }, typeof vb === 'string' ? vb : fmt(vb, digits)), el('td', { class: 'unit' }, unit)));
  };
  const head = el('tr', {}, el('th', {}, 'reading'), ...(a ? [el('th', { class: 'a' }, 'A')] : []), el('th', { class: 'b' }, a ? 'B' : 'value'), el('th', {}, ''));
  row('gloss 20°', 'GU', (r) => r.gloss.gloss_20_gu, 1, 'ISO 2813 specular gloss, 20° geometry (high gloss)');
  row('gloss 60°', 'GU', (r) => r.gloss.gloss_60_gu, 1, 'ISO 2813 specular gloss, 60° geometry');
  row('gloss 85°', 'GU', (r) => r.gloss.gloss_85_gu, 1, 'ISO 2813 specular gloss, 85° geometry (sheen)');
  row('haze (30°, ±2°)', 'HU', (r) => r.gloss.haze_hu, 2, 'ASTM E430 narrow-angle reflection haze');
  row('haze 20° (log)', 'HU', (r) => r.gloss.haze_20_log_hu, 0, 'ASTM E430 Method B, logarithmic scale');
  row('DOI', '', (r) => r.gloss.doi_uncertainty ? `${fmt(r.gloss.doi, 1)} ± ${fmt(r.gloss.doi_uncertainty, 1)}` : fmt(r.gloss.doi, 1), 1, 'ASTM E430 distinctness of image, 0–100');
  row('flop index', '', (r) => r.flop_index, 2, 'Alman\'s flop index from L* at 15°, 45° and 110° aspecular');
  if (b?.albedo) for (const [i, x] of b.albedo.entries()) {
    row(`reflectance ${x.theta_i_deg}°/hemisphere`, '%', (r) => r.albedo?.[i] ? 100 * r.albedo[i].albedo : null, 1,
      `directional-hemispherical reflectance at ${b.albedo_nm} nm, the mirror reflection included`);
  }
  $('meters').replaceChildren(head, ...rows);
  showColour();
  showPlots();
}

function swatchRow(who, geometries) {
  return el('div', { class: 'swatch-row', style: `--n:${geometries.length}` }, el('span', { class: 'who' }, who),
    ...geometries.map((g) => el('div', {
      class: 'swatch' + (g.srgb_clipped ? ' clipped' : ''), style: `background:${g.srgb_hex}`,
      title: `${who} ${g.geometry}: L* ${fmt(g.L)} a* ${fmt(g.a)} b* ${fmt(g.b)}` + (g.srgb_clipped ? ' (outside sRGB: clipped)' : ''),
    })));
}

function showColour() {
  const b = state.readings?.multiangle;
  if (!b) return;
  const comparison = state.readings.target;
  const t = comparison?.read?.multiangle ?? state.target?.read?.multiangle;
  const a = state.pinned?.readings?.multiangle;
  // The standard's geometries, each with the target's where it has one (a CSV may give fewer).
  const on = (list) => b.map((g) => list?.find((x) => x.geometry === g.geometry) ?? { geometry: g.geometry, srgb_hex: 'transparent', L: NaN, a: NaN, b: NaN });
  const rows = [el('div', { class: 'swatch-row', style: `--n:${b.length}` }, el('span', {}),
    ...b.map((g) => el('div', { class: 'swatch-head' }, g.geometry)))];
  if (a) rows.push(swatchRow('A', on(a)));
  rows.push(swatchRow(a ? 'B' : 'this', b));
  if (t) rows.push(swatchRow('target', on(t)));
  $('swatches').replaceChildren(...rows);
  const de = comparison?.de00;
  const head = el('tr', {}, el('th', {}, 'geometry'), el('th', {}, 'L*'), el('th', {}, 'a*'), el('th', {}, 'b*'),
    ...(t ? [el('th', {}, 'target L* a* b*'), el('th', {}, 'ΔE00')] : []),
    ...(a ? [el('th', { class: 'a' }, 'A: L* a* b*')] : []));
  const body = b.map((g) => {
    const tg = t?.find((x) => x.geometry === g.geometry);
    const ag = a?.find((x) => x.geometry === g.geometry);
    const d = de?.find((x) => x.geometry === g.geometry);
    return el('tr', {}, el('td', {}, g.geometry), el('td', {}, fmt(g.L)), el('td', {}, fmt(g.a)), el('td', {}, fmt(g.b)),
      ...(t ? [el('td', {}, tg ? `${fmt(tg.L)} ${fmt(tg.a)} ${fmt(tg.b)}` : '–'), el('td', {}, d ? fmt(d.de00, 2) : '–')] : []),
      ...(a ? [el('td', { class: 'a' }, ag ? `${fmt(ag.L)} ${fmt(ag.a)} ${fmt(ag.b)}` : '–')] : []));
  });
  if (de) body.push(el('tr', {}, el('td', {}, 'mean ΔE00'), el('td', {}), el('td', {}), el('td', {}), el('td', {}),
    el('td', {}, `${fmt(comparison.mean_de00, 2)} (max ${fmt(comparison.max_de00, 2)})`), ...(a ? [el('td', {})] : [])));
  $('colour-table').replaceChildren(head, ...body);
}

// ---------------------------------------------------------------- plots (SVG, drawn here)

// A line plot into `svg`: series [{x, y, colour, label, dash, points}], a log y axis if `logy`.
function plot(svg, { series, marks = [], xlabel, ylabel, logy = false, xmin, xmax, scaleFrom = -Infinity }) {
  const NS = 'http://www.w3.org/2000/svg';
  const W = 420, H = 280, L = 54, R = 10, T = 10, B = 58;
  const make = (tag, attrs, text) => {
    const e = document.createElementNS(NS, tag);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  };
  svg.replaceChildren();
  // The y range from the points at x ≥ scaleFrom (the L* curve's specular peak, hundreds of
  // units high, would flatten the flop the plot is for: it runs off the top, said in a note).
  const ys = series.flatMap((s) => s.y.filter((v, i) => Number.isFinite(v) && (!logy || v > 0) && s.x[i] >= scaleFrom));
  const offScale = series.some((s) => s.y.some((v, i) => s.x[i] < scaleFrom && v > Math.max(...ys)));
  if (!ys.length) return;
  let ymin = Math.min(...ys), ymax = Math.max(...ys);
  if (logy) {
    ymax = Math.pow(10, Math.ceil(Math.log10(ymax)));
    ymin = Math.max(Math.pow(10, Math.floor(Math.log10(ymin))), ymax * 1e-5);
  } else {
    const pad = 0.05 * (ymax - ymin || 1);
    const floor = ymin >= 0 ? 0 : -Infinity;
    ymin = Math.max(floor, Math.floor((ymin - pad) / 10) * 10); ymax = Math.ceil((ymax + pad) / 10) * 10;
  }
  const X = (x) => L + (x - xmin) / (xmax - xmin) * (W - L - R);
  const Y = (y) => {
    const t = logy ? (Math.log10(Math.max(y, ymin)) - Math.log10(ymin)) / (Math.log10(ymax) - Math.log10(ymin)) : (y - ymin) / (ymax - ymin);
    return H - B - t * (H - T - B);
  };
  // Grid and ticks.
  const xstep = (xmax - xmin) > 120 ? 30 : 15;
  for (let x = Math.ceil(xmin / xstep) * xstep; x <= xmax; x += xstep) {
    svg.append(make('line', { x1: X(x), x2: X(x), y1: T, y2: H - B, class: 'grid' }));
    svg.append(make('text', { x: X(x), y: H - B + 14, 'text-anchor': 'middle' }, String(x)));
  }
  const yticks = [];
  if (logy) for (let e = Math.log10(ymin); e <= Math.log10(ymax) + 1e-9; e++) yticks.push(Math.pow(10, e));
  else { const st = (ymax - ymin) > 60 ? 20 : 10; for (let y = ymin; y <= ymax + 1e-9; y += st) yticks.push(y); }
  for (const y of yticks) {
    svg.append(make('line', { x1: L, x2: W - R, y1: Y(y), y2: Y(y), class: 'grid' }));
    svg.append(make('text', { x: L - 4, y: Y(y) + 4, 'text-anchor': 'end' }, logy ? y.toExponential(0).replace('e+', 'e') : String(y)));
  }
  svg.append(make('line', { x1: L, x2: L, y1: T, y2: H - B, class: 'axis' }));
  if (offScale) svg.append(make('text', { x: X(scaleFrom) + 4, y: T + 12 }, 'near-specular peak off scale'));
  svg.append(make('line', { x1: L, x2: W - R, y1: H - B, y2: H - B, class: 'axis' }));
  svg.append(make('text', { x: (L + W - R) / 2, y: H - B + 30, 'text-anchor': 'middle' }, xlabel));
  svg.append(make('text', { x: 12, y: (T + H - B) / 2, 'text-anchor': 'middle', transform: `rotate(-90 12 ${(T + H - B) / 2})` }, ylabel));
  // Series, clipped to the plot's area.
  const clip = make('clipPath', { id: svg.id + '-clip' });
  clip.append(make('rect', { x: L, y: T, width: W - L - R, height: H - T - B }));
  svg.append(clip);
  // A smooth top's mirror: a delta, drawn as a vertical line at the specular angle and named
  // with its reflectance.
  marks.forEach((m, k) => {
    svg.append(make('line', { x1: X(m.x), x2: X(m.x), y1: T, y2: H - B, stroke: m.colour, 'stroke-width': 1.5, 'stroke-dasharray': '2 3' }));
    svg.append(make('text', { x: X(m.x) - 4, y: T + 12 + 13 * k, 'text-anchor': 'end', fill: m.colour }, m.label));
  });
  let lx = L;
  for (const s of series) {
    const pts = s.x.map((x, i) => [x, s.y[i]]).filter(([x, y]) => Number.isFinite(y) && (!logy || y > 0) && x >= xmin && x <= xmax);
    if (s.points) {
      for (const [x, y] of pts) svg.append(make('circle', { cx: X(x), cy: Y(y), r: 3.5, fill: s.colour, 'clip-path': `url(#${svg.id}-clip)` }));
    } else if (pts.length) {
      svg.append(make('polyline', {
        points: pts.map(([x, y]) => `${X(x).toFixed(1)},${Y(y).toFixed(1)}`).join(' '),
        fill: 'none', stroke: s.colour, 'stroke-width': 1.8, 'stroke-dasharray': s.dash || '', 'clip-path': `url(#${svg.id}-clip)`,
      }));
    }
    // The legend sits under the axis label, outside the data.
    svg.append(make('line', { x1: lx, x2: lx + 18, y1: H - 10, y2: H - 10, stroke: s.colour, 'stroke-width': s.points ? 6 : 2, 'stroke-dasharray': s.dash || '' }));
    const label = make('text', { x: lx + 22, y: H - 6 }, s.label);
    svg.append(label);
    lx += 30 + 6.2 * s.label.length;
  }
}

function showPlots() {
  const b = state.readings;
  const a = state.pinned?.readings;
  const t = b?.target?.read ?? state.target?.read;
  const css = (v) => getComputedStyle(document.documentElement).getPropertyValue(v).trim();
  const brdf = [];
  const flop = [];
  const marks = [];
  const add = (r, label, colour, dash) => {
    if (r?.inplane_brdf) {
      brdf.push({ x: r.inplane_brdf.scatter_deg, y: r.inplane_brdf.brdf_per_sr, colour, label, dash });
      if (r.inplane_brdf.mirror_reflectance > 0) {
        marks.push({ x: r.inplane_brdf.incidence_deg, colour, label: `mirror ${fmt(100 * r.inplane_brdf.mirror_reflectance, 1)}%` });
      }
    }
    if (r?.lightness_curve) flop.push({ x: r.lightness_curve.aspecular_deg, y: r.lightness_curve.L, colour, label, dash });
  };
  if (a) add(a, 'A', css('--a'), '');
  add(b, a ? 'B' : 'this formulation', css('--b'), '');
  if (t) add(t, 'target', '#222', '5 3');
  const at45 = (list) => list.filter((g) => g.illumination_deg === 45);
  if (b?.multiangle) {
    const pts = at45(b.multiangle);
    flop.push({ x: pts.map((g) => g.aspecular_deg), y: pts.map((g) => g.L), colour: css('--b'), label: b.standard, points: true });
  }
  if (t?.multiangle && !t.lightness_curve) {
    const pts = at45(t.multiangle);
    flop.push({ x: pts.map((g) => g.aspecular_deg), y: pts.map((g) => g.L), colour: '#222', label: 'target', points: true });
  }
  const inc = b?.inplane_brdf?.incidence_deg ?? Number($('incidence').value);
  plot($('plot-brdf'), { series: brdf, marks, xlabel: `scatter angle (°), specular at +${inc}°`, ylabel: 'BRDF (1/sr, luminance)', logy: true, xmin: -90, xmax: 90 });
  plot($('plot-flop'), { series: flop, xlabel: 'aspecular angle (°)', ylabel: 'L*', xmin: -15, xmax: 110, scaleFrom: 10 });
}

// ---------------------------------------------------------------- files

async function uploadTopography(file) {
  if (!file) return;
  setState('form-state', `reading ${file.name}…`, 'busy');
  try {
    const r = await api('/api/upload/topography?name=' + encodeURIComponent(file.name), file);
    state.topography = r;
    state.f.top = { roughness: { map: r.id } };
    setState('form-state', '');
    showError('');
    buildForm();
    changed();
  } catch (e) {
    setState('form-state', '', '');
    showError(e.message);
  }
}

async function uploadTarget(file) {
  if (!file) return;
  $('target-name').textContent = `reading ${file.name}…`;
  try {
    const r = await api(`/api/upload/target?standard=${$('standard').value}&name=` + encodeURIComponent(file.name), file);
    state.target = r;
    $('target-name').textContent = `target: ${r.name}`;
    showMatchReady();
    $('clear-target').hidden = false;
    showError('');
    readings.go();
  } catch (e) {
    $('target-name').textContent = '';
    showError(e.message);
  }
}

function download(blob, name) {
  const a = el('a', { href: URL.createObjectURL(blob), download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

async function exportTable(format) {
  const button = $('export-' + format);
  const label = button.textContent;
  button.textContent = 'computing the table…';
  button.disabled = true;
  try {
    const r = await api('/api/export/' + format, { formulation: state.f }, { blob: true });
    const name = (r.headers.get('content-disposition') || '').match(/filename="([^"]+)"/)?.[1] || 'coating.' + format;
    download(await r.blob(), name);
  } catch (e) {
    showError(e.message);
  } finally {
    button.textContent = label;
    button.disabled = false;
  }
}

async function loadExample(name) {
  const r = await api('/api/examples/' + encodeURIComponent(name));
  setFormulation(r.formulation);
}

function setFormulation(f) {
  state.f = f;
  state.invalid = null;
  buildForm();
  changed();
}

// ---------------------------------------------------------------- the way back: match, sensitivity

// What the two panels vary: per panel, the constituents the formulation offers (from the server:
// name, label, value and default bounds) and the user's choices {on, lo, hi} by name, kept while
// the formulation changes.
const panels = {
  match: { table: 'match-vary', offered: [], chosen: {}, defaultOn: (n) => n === 'tilt' || n === 'coverage' || n.startsWith('concentration:') },
  sens: { table: 'sens-vary', offered: [], chosen: {}, defaultOn: (n) => n !== 'tio2' },
};
let outputsOffered = [];
const outputsChosen = {};
const outputDefault = (name) => /^(gu20|gu60|haze|doi|flop|dE00|L@.*)$/.test(name);

// The pigments a match uses (docs/lab.md, POST /api/match): the formulation's own, library
// pigments ticked, or up to N selected by gonio from those ticked (none ticked: the library).
function matchPigments() {
  const from = document.querySelector('input[name=match-pigments]:checked').value;
  const names = [...document.querySelectorAll('#match-library input:checked')].map((i) => i.value);
  if (from === 'library') return { from, names };
  if (from === 'select') {
    return { from, max: number('match-select-max') ?? 3, candidates: names.length ? names : undefined, finalists: number('match-finalists') };
  }
  return { from };
}

const pigmentName = (name) => name.replace(/_/g, ' ');

// The constituents of the formulation (the match's with its pigments choice), refreshed a moment
// after the last change.
let constituentsTimer = null;
function constituentsSoon() {
  clearTimeout(constituentsTimer);
  constituentsTimer = setTimeout(refreshConstituents, 250);
}

async function refreshConstituents() {
  const standard = $('standard').value;
  try {
    const own = await api('/api/constituents', { formulation: state.f, standard });
    panels.sens.offered = own.constituents;
    outputsOffered = own.outputs;
    showOutputs();
    const pigments = matchPigments();
    const m = pigments.from !== 'library' ? own : await api('/api/constituents', { formulation: state.f, standard, pigments });
    panels.match.offered = m.constituents;
    $('match-state').textContent = '';
  } catch (e) {
    // A formulation the library refuses is marked in the form; a pigment choice here.
    if (e.status === 400 && matchPigments().from === 'library') setState('match-state', e.message, 'error');
    panels.match.offered = [];
  }
  showVary(panels.match);
  showVary(panels.sens);
  showMatchReady();
}

function showVary(panel) {
  const head = el('tr', {}, el('th', {}, 'vary'), el('th', {}, 'constituent'), el('th', {}, 'now'), el('th', {}, 'from'), el('th', {}, 'to'));
  const rows = panel.offered.map((c) => {
    const chosen = panel.chosen[c.name] ?? (panel.chosen[c.name] = { on: panel.defaultOn(c.name), lo: c.lo, hi: c.hi });
    const box = el('input', { type: 'checkbox', 'aria-label': 'vary ' + c.name, 'data-name': c.name });
    box.checked = chosen.on;
    box.addEventListener('change', () => { chosen.on = box.checked; showMatchReady(); });
    const bound = (key) => {
      const input = el('input', { type: 'number', step: 'any', 'aria-label': `${c.name} ${key === 'lo' ? 'from' : 'to'}`, 'data-name': c.name, 'data-bound': key });
      input.value = chosen[key];
      input.addEventListener('change', () => { if (input.value !== '' && Number.isFinite(Number(input.value))) chosen[key] = Number(input.value); });
      return input;
    };
    return el('tr', {}, el('td', {}, box), el('td', { class: 'name', title: c.name }, c.label), el('td', {}, String(round(c.value))),
      el('td', {}, bound('lo')), el('td', {}, bound('hi')));
  });
  $(panel.table).replaceChildren(head, ...rows);
}

function varyOf(panel) {
  return panel.offered.filter((c) => panel.chosen[c.name]?.on).map((c) => ({ name: c.name, lo: panel.chosen[c.name].lo, hi: panel.chosen[c.name].hi }));
}

function showOutputs() {
  const list = document.querySelector('#sens-outputs .output-list');
  list.replaceChildren(...outputsOffered.map((o) => {
    if (outputsChosen[o.name] === undefined) outputsChosen[o.name] = outputDefault(o.name);
    const box = el('input', { type: 'checkbox', value: o.name });
    box.checked = outputsChosen[o.name];
    box.addEventListener('change', () => { outputsChosen[o.name] = box.checked; countOutputs(); });
    return el('label', { title: o.name }, box, ' ' + o.words);
  }));
  countOutputs();
}

function countOutputs() {
  const n = outputsOffered.filter((o) => outputsChosen[o.name]).length;
  document.querySelector('#sens-outputs summary').textContent = `readings judged: ${n} of ${outputsOffered.length} (choose)`;
}

function showMatchReady() {
  // A selection varies its pigments' concentrations besides the constituents ticked.
  const ready = state.target && (varyOf(panels.match).length > 0 || matchPigments().from === 'select') && !jobs.match;
  $('match-run').disabled = !ready;
  $('match-hint').hidden = !!state.target;
}

const number = (id) => { const v = $(id).value; return v === '' ? undefined : Number(v); };

// A job on the server (docs/lab.md, "Jobs"): started by POST, followed by polling, cancelled by
// its Cancel button. `show(job)` gets every answer; `done(result)` the result.
const jobs = { match: null, sens: null };
async function runJob(kind, path, body, { progress, line, run, cancel, show, done }) {
  $(progress).hidden = false;
  $(progress).removeAttribute('value');
  $(line).textContent = 'starting…';
  $(run).disabled = true;
  let job;
  try {
    job = await api(path, body);
  } catch (e) {
    $(progress).hidden = true;
    $(line).textContent = '';
    $(run).disabled = false;
    showError(e.message);
    if (kind === 'match') showMatchReady();
    return;
  }
  showError('');
  jobs[kind] = job.id;
  $(cancel).disabled = false;
  $(cancel).onclick = () => { api(`/api/jobs/${job.id}/cancel`, {}).catch((e) => showError(e.message)); };
  while (true) {
    await new Promise((r) => setTimeout(r, 400));
    try { job = await api('/api/jobs/' + job.id); } catch (e) { showError(e.message); break; }
    if (job.total) { $(progress).max = job.total; $(progress).value = job.readings; } else $(progress).removeAttribute('value');
    show(job);
    if (job.state !== 'running' && job.state !== 'cancelling') break;
  }
  jobs[kind] = null;
  $(cancel).disabled = true;
  $(run).disabled = false;
  $(progress).hidden = job.state === 'done' ? true : $(progress).hidden;
  if (job.state === 'done') done(job.result);
  else if (job.state === 'failed') showError(job.error);
  $(progress).hidden = true;
  if (kind === 'match') showMatchReady();
}

const seconds = (s) => s < 90 ? `${s.toFixed(0)} s` : `${(s / 60).toFixed(1)} min`;

async function startMatch() {
  const body = { formulation: state.f, target: state.target.id, standard: $('standard').value, vary: varyOf(panels.match),
    pigments: matchPigments(), walks: number('match-walks'), starts: number('match-starts'), iterations: number('match-iterations') };
  $('match-result').replaceChildren();
  await runJob('match', '/api/match', body, {
    progress: 'match-progress', line: 'match-line', run: 'match-run', cancel: 'match-cancel',
    show: (j) => {
      const best = j.best === null ? '' : ` · best mean ΔE00 so far ${fmt(j.best, 2)}`;
      // A selection's step: the screen (its readings are combinations), then each finalist.
      const step = j.stage?.step === 'screen' ? `screened ${j.readings} of ${j.stage.combinations} combinations`
        : j.stage?.step === 'finalist' ? `finalist ${j.stage.number} of ${j.stage.of} (${j.stage.pigments.map(pigmentName).join(' + ')}): ${j.readings} readings`
          : `${j.readings} readings`;
      const screenBest = j.best === null ? '' : ` · best screen ΔE00 ${fmt(j.best, 2)}`;
      const what = j.state === 'cancelled' ? (j.stage ? `cancelled in ${step}` : `cancelled after ${j.readings} readings`) : j.state === 'failed' ? 'failed'
        : j.stage?.step === 'screen' ? step + screenBest : step + best;
      $('match-line').textContent = `${what} · ${seconds(j.seconds)}` + (j.line && j.state === 'running' ? ` · ${j.line}` : '');
    },
    done: showMatch,
  });
}

// The match's result: the fitted formulation fills the form (its readings against the target
// follow), and its ΔE00 per geometry, start against fitted, and its values with σ are shown.
function showMatch(m) {
  state.pinned = null;
  $('picture-a').hidden = true;
  setFormulation(m.formulation);
  const sel = m.selection;
  $('match-line').textContent = sel ? `done: ${sel.combinations} combinations screened, ${sel.finalists.length} finalists matched in ${seconds(sel.seconds)}; the form holds the chosen one, fitted`
    : `done: ${m.evaluations} readings in ${seconds(m.seconds)}; the form holds the fitted formulation`;
  const cls = (a, b) => b < a - 0.005 ? 'better' : b > a + 0.005 ? 'worse' : '';
  const de = el('table', { class: 'numbers', id: 'match-de00' },
    el('tr', {}, el('th', {}, 'geometry'), el('th', {}, sel ? 'ΔE00 screened' : 'ΔE00 start'), el('th', {}, 'ΔE00 fitted')),
    ...m.geometries.map((g) => el('tr', {}, el('td', {}, g.name), el('td', {}, fmt(g.de00_start, 2)),
      el('td', { class: cls(g.de00_start, g.de00_fitted) }, fmt(g.de00_fitted, 2)))),
    el('tr', {}, el('td', {}, 'mean'), el('td', {}, fmt(m.mean_de00_start, 2)),
      el('td', { class: cls(m.mean_de00_start, m.mean_de00_fitted) }, fmt(m.mean_de00_fitted, 2))));
  const sd = (c) => c.sigma === null ? '–' : `± ${round(c.sigma)}`;
  const values = el('table', { class: 'numbers', id: 'match-values' },
    el('tr', {}, el('th', {}, 'constituent'), el('th', {}, 'start'), el('th', {}, 'fitted'), el('th', {}, 'σ (1 sd)'), el('th', {}, 'bounds')),
    ...m.constituents.map((c) => el('tr', { title: c.at_bound ? 'at a bound: σ describes a constrained value; widen the bounds' : '' },
      el('td', {}, ...c.name.split(':').flatMap((part, i) => i ? [':', el('wbr'), part] : [part])), el('td', {}, String(round(c.start))), el('td', {}, String(round(c.fitted)), ...(c.at_bound ? [el('br'), el('span', { class: 'unit' }, 'at a bound')] : [])),
      el('td', {}, sd(c)), el('td', {}, `${round(c.lo)} – ${round(c.hi)}`))));
  $('match-result').replaceChildren(
    ...(sel ? selectionParts(sel) : []),
    el('div', { class: 'verdict' }, `Mean ΔE00 ${fmt(m.mean_de00_start, 2)} → ${fmt(m.mean_de00_fitted, 2)} at the ${m.standard} geometries the target has (${m.objective} objective; residual sd ${fmt(m.residual_sd, 2)})${sel ? ', from the screen\'s concentrations' : ''}.`),
    el('div', { class: 'plots' }, el('div', { class: 'scroll' }, de), el('div', { class: 'scroll' }, values)));
}

// A selection's choice and its finalists (each matched in full; the chosen one ended lowest).
function selectionParts(sel) {
  const names = (list) => list.map(pigmentName).join(' + ');
  const rows = sel.finalists.map((f, i) => el('tr', { class: i === sel.chosen ? 'chosen' : '' },
    // Each pigment's name whole: a narrow window breaks the line between pigments only.
    el('td', {}, (i === sel.chosen ? '✓ ' : ''), ...f.pigments.flatMap((p, k) => [...(k ? [' + '] : []), el('span', { class: 'pigment-name' }, pigmentName(p))])),
    el('td', {}, f.concentrations.map((c) => String(round(c))).join(' + ')),
    el('td', {}, fmt(f.screen_score, 2)), el('td', {}, fmt(f.mean_de00, 2))));
  return [
    el('div', { class: 'verdict', id: 'match-chosen' }, `gonio chose ${names(sel.pigments)}: the lowest of ${sel.finalists.length} finalists, from ${sel.combinations} combinations of ${sel.candidates.length} candidates screened.`),
    el('div', { class: 'scroll' }, el('table', { class: 'numbers', id: 'match-finalists-table', 'aria-label': 'finalists' },
      el('tr', {}, el('th', {}, 'finalist'), el('th', {}, 'fitted concentrations'), el('th', {}, 'screen ΔE00'), el('th', {}, 'mean ΔE00')), ...rows)),
  ];
}

async function startSensitivity() {
  const outputs = outputsOffered.filter((o) => outputsChosen[o.name]).map((o) => o.name);
  const body = { formulation: state.f, standard: $('standard').value, vary: varyOf(panels.sens), outputs,
    method: $('sens-method').value, samples: number('sens-samples'), walks: number('sens-walks') };
  await runJob('sens', '/api/sensitivity', body, {
    progress: 'sens-progress', line: 'sens-line', run: 'sens-run', cancel: 'sens-cancel',
    show: (j) => {
      const what = j.state === 'cancelled' ? 'cancelled after' : 'readings';
      $('sens-line').textContent = `${what} ${j.readings} of ${j.total} · ${seconds(j.seconds)}`;
    },
    done: showSensitivity,
  });
}

// The chart: for each reading, one bar per constituent. Morris: μ* over the largest μ* of that
// reading (so that readings in GU and in L* share one axis), the figure μ* ± its 95% interval in
// the reading's units; Sobol: the total index ST ± its 95% interval.
// Three significant figures, an exponent below 0.01.
const short = (v) => !Number.isFinite(v) ? '–' : v === 0 ? '0' : Math.abs(v) < 0.01 ? v.toExponential(0) : String(Number(v.toPrecision(3)));
const PALETTE = ['#1f5fa8', '#b5561c', '#2e8540', '#8a3ea8', '#b0931c', '#1c9aa0', '#a8324a', '#555555'];
let lastSensitivity = null;
function showSensitivity(s) {
  lastSensitivity = s;
  $('sens-summary').textContent = s.summary;
  drawSensitivity(s);
}

// Drawn at the chart's own width in pixels (its text stays legible in a narrow window), again
// whenever that width changes.
function drawSensitivity(s) {
  const svg = $('sens-chart');
  svg.removeAttribute('hidden');
  const NS = 'http://www.w3.org/2000/svg';
  const make = (tag, attrs, text) => {
    const e = document.createElementNS(NS, tag);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  };
  const morris = s.method === 'morris';
  const inputs = s.inputs.map((i) => i.name);
  const W = Math.max(300, svg.clientWidth || 600);
  const nameW = Math.min(150, 0.3 * W), figW = 88, barH = 13, gap = 3;
  const x0 = nameW + 6, x1 = W - figW - 6;
  svg.replaceChildren();
  // Legend: one swatch per constituent.
  let lx = 0, ly = 14;
  inputs.forEach((name, i) => {
    const w = 22 + 7 * name.length;
    if (lx + w > W) { lx = 0; ly += 18; }
    svg.append(make('rect', { x: lx, y: ly - 10, width: 12, height: 12, fill: PALETTE[i % PALETTE.length] }));
    svg.append(make('text', { x: lx + 16, y: ly }, name));
    lx += w + 10;
  });
  let y = ly + 14;
  $('sens-note').textContent = morris
    ? 'Each bar: μ* divided by the largest μ* of that reading (readings in GU and in L* share one axis), its 95% interval as a whisker; beside it μ* ± that interval in the reading\'s own units.'
    : 'Each bar: the total Sobol index ST, its 95% interval as a whisker; beside it ST ± that interval.';
  y -= 4;
  const X = (v) => x0 + Math.max(0, Math.min(1.1, v)) / 1.1 * (x1 - x0);
  s.outputs.forEach((o, k) => {
    const idx = o.indices;
    const value = (n) => morris ? idx.mu_star[n] : idx.st[n];
    const conf = (n) => morris ? idx.mu_star_conf[n] : idx.st_conf[n];
    const scale = morris ? Math.max(...inputs.map(value)) || 1 : 1;
    const top = y + 6;
    const h = inputs.length * (barH + gap);
    svg.append(make('line', { x1: 0, x2: W, y1: top - 3, y2: top - 3, class: 'grid' }));
    const words = s.words?.[k] ?? o.output;
    const label = make('text', { x: 0, y: top + h / 2 + 4, class: 'chart-output' }, 6.6 * words.length <= nameW ? words : o.output);
    label.append(make('title', {}, `${o.output}: base ${fmt(o.base, 2)}, noise sd ${fmt(o.noise, 3)}`));
    svg.append(label);
    inputs.forEach((n, i) => {
      const by = top + i * (barH + gap);
      const v = value(n) / scale, c = conf(n) / scale;
      const bar = make('rect', { x: x0, y: by, width: Math.max(0.5, X(v) - x0), height: barH, fill: PALETTE[i % PALETTE.length], class: 'bar', 'data-output': o.output, 'data-input': n });
      bar.append(make('title', {}, `${n} → ${o.output}: ${morris ? 'μ*' : 'ST'} ${fmt(value(n), 3)} ± ${fmt(conf(n), 3)}`));
      svg.append(bar);
      svg.append(make('line', { x1: X(v - c), x2: X(v + c), y1: by + barH / 2, y2: by + barH / 2, stroke: '#222', 'stroke-width': 1.2 }));
      svg.append(make('text', { x: x1 + 6, y: by + barH - 2, class: 'chart-figure' }, `${short(value(n))} ± ${short(conf(n))}`));
    });
    y = top + h + 4;
  });
  // The axis: 0 and 1 (the largest μ*, or ST = 1).
  for (const t of [0, 0.5, 1]) {
    svg.append(make('line', { x1: X(t), x2: X(t), y1: ly + 12, y2: y, class: 'grid' }));
    svg.append(make('text', { x: X(t), y: y + 12, 'text-anchor': 'middle' }, String(t)));
  }
  svg.setAttribute('viewBox', `0 0 ${W} ${y + 18}`);
  svg.setAttribute('height', y + 18);
}

function startPanels() {
  let drawnWidth = 0;
  new ResizeObserver(() => {
    const w = $('sens-chart').clientWidth;
    if (lastSensitivity && w && Math.abs(w - drawnWidth) > 1) { drawnWidth = w; drawSensitivity(lastSensitivity); }
  }).observe($('sensitivity-card'));
  $('match-run').addEventListener('click', startMatch);
  $('sens-run').addEventListener('click', startSensitivity);
  $('sens-method').addEventListener('change', () => {
    const morris = $('sens-method').value === 'morris';
    $('sens-samples-label').textContent = morris ? 'trajectories' : 'base points';
    $('sens-samples').placeholder = morris ? '20' : '32';
  });
  const library = state.pigments.filter((p) => p.library);
  $('match-library').replaceChildren(...library.map((p) => {
    const box = el('input', { type: 'checkbox', value: p.name });
    box.addEventListener('change', refreshConstituents);
    return el('label', { title: p.colour_index }, box, ` ${p.name.replace(/_/g, ' ')} (${p.colour_index})`);
  }));
  document.querySelectorAll('input[name=match-pigments]').forEach((r) => r.addEventListener('change', () => {
    const from = matchPigments().from;
    $('match-library').hidden = from === 'formulation';
    $('match-select').hidden = from !== 'select';
    refreshConstituents();
  }));
  $('standard').addEventListener('change', refreshConstituents);
}

// ---------------------------------------------------------------- start

async function start() {
  const [examples, lightings, pigments] = await Promise.all([api('/api/examples'), api('/api/lightings'), api('/api/pigments')]);
  state.pigments = pigments;
  $('example').replaceChildren(el('option', { value: '' }, '—'), ...examples.map((e) => el('option', { value: e.name, title: e.title }, e.name.replace(/_/g, ' '))));
  $('lighting').replaceChildren(...lightings.map((l) => el('option', { value: l.name, title: l.description }, l.name)));
  $('example').addEventListener('change', () => { if ($('example').value) loadExample($('example').value); });
  $('lighting').addEventListener('change', () => { picture.go(); if (state.pinned) renderPinned(); });
  // The target is read again by the server at the new standard (or incidence) with the readings.
  $('standard').addEventListener('change', () => { readings.go(); if (state.pinned) pinnedReadings(); });
  $('incidence').addEventListener('change', () => { readings.go(); if (state.pinned) pinnedReadings(); });
  $('open-toml').addEventListener('change', async (ev) => {
    const file = ev.target.files[0];
    if (!file) return;
    try {
      const r = await api('/api/formulation/from-toml', new Blob([await file.text()]));
      $('example').value = '';
      setFormulation(r.formulation);
      showError('');
    } catch (e) { showError(`${file.name}: ${e.message}`); }
    ev.target.value = '';
  });
  $('save-toml').addEventListener('click', async () => {
    try {
      const r = await api('/api/formulation/to-toml', { formulation: state.f }, { blob: true });
      download(await r.blob(), 'formulation.toml');
    } catch (e) { showError(e.message); }
  });
  $('open-target').addEventListener('change', (ev) => { uploadTarget(ev.target.files[0]); ev.target.value = ''; });
  $('clear-target').addEventListener('click', () => {
    state.target = null;
    showMatchReady();
    $('target-name').textContent = '';
    $('clear-target').hidden = true;
    readings.go();
  });
  $('pin').addEventListener('click', pin);
  startPanels();
  $('export-png').addEventListener('click', async () => {
    if (!pictureUrl) return;
    download(await (await fetch(pictureUrl)).blob(), 'coating.png');
  });
  $('export-gbrdf').addEventListener('click', () => exportTable('gbrdf'));
  $('export-mitsuba').addEventListener('click', () => exportTable('mitsuba'));
  let f = null;
  const m = location.hash.match(/#f=([A-Za-z0-9_-]+)/);
  if (m) {
    try { f = decode(m[1]); } catch (_) { showError('The link\'s formulation could not be read; starting from an example.'); }
  }
  if (f) setFormulation(f);
  else { $('example').value = 'silver_metallic'; await loadExample('silver_metallic'); }
}

// Pin the current formulation as A: its readings and picture stay beside B's.
function pin() {
  if (!state.readings) return;
  state.pinned = { f: JSON.parse(JSON.stringify(state.f)), readings: state.readings };
  const img = $('picture-a').querySelector('img');
  img.src = $('picture').src;
  $('picture-a').hidden = false;
  $('pin').textContent = 'Pin again as A';
  showReadings();
}

async function pinnedReadings() {
  const body = { formulation: state.pinned.f, standard: $('standard').value, incidence_deg: Number($('incidence').value), channel: 'readings-A' };
  try {
    state.pinned.readings = await api('/api/readings', body);
    showReadings();
  } catch (e) { showError(e.message); }
}

async function renderPinned() {
  try {
    const r = await api('/api/picture', { formulation: state.pinned.f, lighting: $('lighting').value, quality: 'converged', channel: 'picture-A' }, { blob: true });
    $('picture-a').querySelector('img').src = URL.createObjectURL(await r.blob());
  } catch (e) { if (e.status !== 409) showError(e.message); }
}

start().catch((e) => showError('The lab could not start: ' + e.message));
