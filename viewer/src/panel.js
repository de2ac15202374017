// The page's text and charts: title, verdict, warnings, parameters, the histogram of area per
// thickness range (SVG), the colour bar and the list of regions (thin, then the specks set
// aside from the check's list, then thick).

import { colourValues, cssColour, niceTicks, numberText, viridis } from './colour_map.js';

const svgNS = 'http://www.w3.org/2000/svg';

function svg(tag, attributes, text) {
  const element = document.createElementNS(svgNS, tag);
  for (const [k, v] of Object.entries(attributes)) element.setAttribute(k, v);
  if (text !== undefined) element.textContent = text;
  return element;
}

function point(p) {
  return '(' + p.map((x) => numberText(x, 5)).join(', ') + ')';
}

export function fillHeader(meta) {
  document.title = `${meta.title} — bemshape thickness report`;
  document.getElementById('title').textContent = meta.title;
  document.getElementById('subtitle').textContent =
    `${meta.faces.toLocaleString('en')} faces, ${meta.vertices.toLocaleString('en')} vertices; ` +
    `lengths in ${meta.units}, areas in ${meta.units}²`;
  const verdict = document.getElementById('verdict');
  const word = meta.verdict || '';
  verdict.className = word === 'PASS' ? 'pass' : word === 'FAIL' ? 'fail' : 'none';
  verdict.replaceChildren();
  if (word) {
    const w = document.createElement('span');
    w.className = 'word';
    w.textContent = word;
    verdict.append(w);
  }
  verdict.append(meta.verdict_text || (word ? '' : 'No check was requested.'));
  const warnings = document.getElementById('warnings');
  warnings.replaceChildren();
  for (const line of meta.warnings || []) {
    const p = document.createElement('p');
    p.className = 'warning';
    p.textContent = `Warning: ${line}`;
    warnings.append(p);
  }
  const table = document.getElementById('parameters');
  for (const [name, value] of meta.parameters) {
    const row = table.insertRow();
    row.insertCell().textContent = name;
    row.insertCell().textContent = value;
  }
}

/// Colour bar: the ramp, round ticks and the thresholds (dashed).
export function fillColourBar(meta) {
  const [lo, hi] = meta.colour_range;
  document.getElementById('colourbar-label').textContent = `${meta.quantity} [${meta.units}]`;
  const ramp = document.getElementById('colourbar-ramp');
  const context = ramp.getContext('2d');
  const image = context.createImageData(ramp.width, 1);
  const values = Float32Array.from({ length: ramp.width }, (_, i) => i / (ramp.width - 1));
  const rgb = colourValues(values, 0, 1, new Uint8Array(3 * ramp.width));
  for (let i = 0; i < ramp.width; ++i) {
    image.data.set(rgb.subarray(3 * i, 3 * i + 3), 4 * i);
    image.data[4 * i + 3] = 255;
  }
  context.putImageData(image, 0, 0);
  // x in percent of the bar's width, y in pixels: the SVG is not scaled, so text stays upright.
  const ticks = document.getElementById('colourbar-ticks');
  const x = (v) => `${hi > lo ? (100 * (v - lo)) / (hi - lo) : 50}%`;
  for (const v of niceTicks(lo, hi, 5)) {
    ticks.append(svg('line', { x1: x(v), x2: x(v), y1: 0, y2: 4, stroke: '#1d2430' }));
    ticks.append(svg('text', { x: x(v), y: 16, 'text-anchor': 'middle' }, numberText(v)));
  }
  const label = document.getElementById('colourbar-label');
  for (const [t, name] of [[meta.min_thickness, 'minimum'], [meta.max_thickness, 'maximum']]) {
    if (t === null || t === undefined) continue;
    if (t >= lo && t <= hi)
      ticks.append(svg('line', { x1: x(t), x2: x(t), y1: -16, y2: 4, stroke: '#ff2d55', 'stroke-width': 2, 'stroke-dasharray': '3 2' }));
    label.textContent += ` · ${name} ${numberText(t)} dashed`;
  }
}

/// The histogram of area per thickness range as an SVG bar chart: bars coloured by the colour
/// map at the bin's middle, thresholds dashed, each bar's range and area in its tooltip.
export function fillHistogram(meta) {
  const box = document.getElementById('histogram');
  const { edges, area, other_area: otherArea } = meta.histogram;
  if (!edges || edges.length < 2) {
    box.innerHTML = '<p class="empty">No histogram in this report.</p>';
    return;
  }
  const W = 330, H = 160, left = 44, right = 14, top = 20, bottom = 30;
  const chart = svg('svg', { viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': 'histogram of area per thickness range' });
  chart.id = 'histogram-chart';
  const x0 = edges[0], x1 = edges[edges.length - 1];
  const total = area.reduce((a, b) => a + b, 0) + otherArea;
  const top_area = Math.max(...area, 1e-300);
  const x = (v) => left + ((W - left - right) * (v - x0)) / (x1 - x0 || 1);
  const y = (a) => H - bottom - ((H - top - bottom) * a) / top_area;
  const [lo, hi] = meta.colour_range;
  for (let k = 0; k < area.length; ++k) {
    const middle = 0.5 * (edges[k] + edges[k + 1]);
    const bar = svg('rect', {
      x: x(edges[k]) + 0.5, y: y(area[k]), width: Math.max(x(edges[k + 1]) - x(edges[k]) - 1, 0.5),
      height: Math.max(H - bottom - y(area[k]), 0), fill: cssColour(viridis(hi > lo ? (middle - lo) / (hi - lo) : 0.5)),
      class: 'bar',
    });
    bar.append(svg('title', {}, `${numberText(edges[k])} – ${numberText(edges[k + 1])} ${meta.units}: area ${numberText(area[k])} ${meta.units}² (${numberText((100 * area[k]) / total, 3)} %)`));
    chart.append(bar);
  }
  chart.append(svg('line', { x1: left, x2: W - right, y1: H - bottom, y2: H - bottom, stroke: '#5b6675' }));
  chart.append(svg('line', { x1: left, x2: left, y1: top, y2: H - bottom, stroke: '#5b6675' }));
  for (const v of niceTicks(x0, x1, 5)) {
    chart.append(svg('line', { x1: x(v), x2: x(v), y1: H - bottom, y2: H - bottom + 3, stroke: '#5b6675' }));
    chart.append(svg('text', { x: x(v), y: H - bottom + 13, 'text-anchor': 'middle' }, numberText(v)));
  }
  chart.append(svg('text', { x: (left + W - right) / 2, y: H - 3, 'text-anchor': 'middle' }, `${meta.quantity} [${meta.units}]`));
  for (const a of niceTicks(0, top_area, 3)) {
    chart.append(svg('text', { x: left - 4, y: y(a) + 3, 'text-anchor': 'end' }, numberText(a, 3)));
  }
  chart.append(svg('text', { x: 2, y: 10 }, `area [${meta.units}²]`));
  for (const t of [meta.min_thickness, meta.max_thickness]) {
    if (t === null || t === undefined || t < x0 || t > x1) continue;
    chart.append(svg('line', { x1: x(t), x2: x(t), y1: top, y2: H - bottom, stroke: '#ff2d55', 'stroke-dasharray': '4 3' }));
  }
  box.replaceChildren(chart);
  if (otherArea > 0) {
    const note = document.createElement('p');
    note.className = 'sub';
    note.textContent = `Not measurable (no opposite wall within reach): ${numberText(otherArea)} ${meta.units}² (${numberText((100 * otherArea) / total, 3)} %).`;
    box.append(note);
  }
}

/// One button per region; `select(i)` is called with the region's index when it is clicked.
export function fillRegions(meta, select) {
  const list = document.getElementById('regions');
  list.replaceChildren();
  if (meta.regions.length === 0) {
    const item = document.createElement('li');
    item.className = 'empty';
    item.textContent = meta.min_thickness !== null || meta.max_thickness !== null ? 'No region beyond the thresholds.' : 'No thresholds given, so no regions.';
    list.append(item);
    return [];
  }
  return meta.regions.map((region, i) => {
    const item = document.createElement('li');
    const button = document.createElement('button');
    button.type = 'button';
    button.className = 'region';
    button.dataset.index = i;
    const head = document.createElement('div');
    head.className = 'head';
    const kind = document.createElement('span');
    kind.className = `kind-${region.kind}`;
    kind.textContent = `${region.kind} #${region.rank}`;
    head.append(kind, ` · ${region.kind === 'thick' ? 'max' : 'min'} ${numberText(region.extreme)}`);
    const detail = document.createElement('div');
    detail.className = 'detail';
    detail.textContent = `at ${point(region.extreme_location)}, area ${numberText(region.area)}, ${region.face_count} faces`;
    button.append(head, detail);
    button.addEventListener('click', () => select(i));
    item.append(button);
    list.append(item);
    return button;
  });
}

/// The warning of a surface measured as given where it crosses itself: the defect colour,
/// how many faces carry it and each region with what and why. Hidden without defects.
export function fillDefects(meta) {
  const box = document.getElementById('defects');
  const defects = meta.defects ?? [];
  if (defects.length === 0) return;
  box.hidden = false;
  const swatch = document.createElement('span');
  swatch.className = 'swatch';
  swatch.style.background = cssColour(meta.defect_colour);
  const head = document.createElement('div');
  head.append(swatch, `The surface crosses itself in ${defects.length} region${defects.length === 1 ? '' : 's'} ` +
    `that could not be repaired; the ${meta.defect_face_count.toLocaleString('en')} faces within h0 of ` +
    `${defects.length === 1 ? 'it are' : 'them are'} drawn in this colour: their thickness is measured on the surface as given, not the part's.`);
  const list = document.createElement('ul');
  for (const d of defects) {
    const item = document.createElement('li');
    item.textContent = d.text;
    list.append(item);
  }
  box.replaceChildren(head, list);
}
