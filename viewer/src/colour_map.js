// The colour map of every bemshape picture: matplotlib's "viridis" as 9 anchors at t = 0, 1/8,
// …, 1 with linear interpolation, the same table as apps/output/colour_map.hpp (PLY colours),
// so the page and the PLY files show a value in the same colour.

const anchors = [
  [68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141],
  [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37],
];

/// Grey of values with no colour (NaN: no measurable thickness).
export const noValueColour = [160, 160, 160];

/// [r, g, b] (0…255) of t ∈ [0, 1], clamped; NaN gives noValueColour.
export function viridis(t) {
  if (Number.isNaN(t)) return noValueColour;
  t = Math.min(Math.max(t, 0), 1);
  const u = t * (anchors.length - 1);
  const i = Math.min(Math.floor(u), anchors.length - 2);
  const w = u - i;
  const a = anchors[i], b = anchors[i + 1];
  return [0, 1, 2].map((k) => Math.round((1 - w) * a[k] + w * b[k]));
}

export function cssColour([r, g, b]) {
  return `rgb(${r},${g},${b})`;
}

/// Fills `out` (Uint8Array, 3 per value) with the colours of `values` between lo and hi.
export function colourValues(values, lo, hi, out) {
  const span = hi > lo ? hi - lo : 1;
  // A 1024-entry table: finer than the 8-bit colours it produces.
  const table = new Uint8Array(3 * 1024);
  for (let k = 0; k < 1024; ++k) table.set(viridis(k / 1023), 3 * k);
  for (let i = 0; i < values.length; ++i) {
    const v = values[i];
    if (Number.isNaN(v)) {
      out.set(noValueColour, 3 * i);
      continue;
    }
    const k = Math.round(Math.min(Math.max((v - lo) / span, 0), 1) * 1023);
    out[3 * i] = table[3 * k];
    out[3 * i + 1] = table[3 * k + 1];
    out[3 * i + 2] = table[3 * k + 2];
  }
  return out;
}

/// Round tick values (1, 2, 5 × 10^m steps) covering [lo, hi] with about `count` ticks.
export function niceTicks(lo, hi, count) {
  if (!(hi > lo)) return [lo];
  const raw = (hi - lo) / Math.max(count, 1);
  const decade = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * decade).find((s) => s >= raw * (1 - 1e-9));
  const ticks = [];
  for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step)
    ticks.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  return ticks;
}

/// Short text of a number: 4 significant digits, no trailing zeros.
export function numberText(x, digits = 4) {
  if (!Number.isFinite(x)) return String(x);
  if (x !== 0 && (Math.abs(x) >= 1e6 || Math.abs(x) < 1e-3)) return x.toExponential(digits - 1).replace(/\.?0+e/, 'e');
  return String(Number(x.toPrecision(digits)));
}
