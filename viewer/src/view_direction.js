// Where to put the camera to see a point of the surface: along a direction from the point
// that no part of the surface blocks within the viewing distance (a thin spot on the wall of
// a hole is seen through the hole's opening, not through the plate).
//
// Candidates are the face normal n, its mixes with the preferred direction (the current view)
// and 96 directions spread evenly over the sphere (a Fibonacci lattice), each facing the
// surface's outside (d·n > 0.1). A candidate is clear when the segment from the point to the
// camera hits no triangle (Möller–Trumbore); the clear candidate with the largest
// d·n + 0.5·d·preferred wins. Only triangles whose bounding box reaches within `distance` of
// the point are tested. If every candidate is blocked, the one whose first hit is farthest is
// taken, with the camera moved in front of that hit.

const latticeSize = 96;
/// Ray-triangle tests one choice may take (about a second of JavaScript); beyond it the
/// lattice is thinned.
const testBudget = 3e7;

function lattice(count) {
  const out = [];
  const golden = Math.PI * (3 - Math.sqrt(5));
  for (let i = 0; i < count; ++i) {
    const z = 1 - (2 * (i + 0.5)) / count;
    const r = Math.sqrt(1 - z * z);
    out.push([r * Math.cos(golden * i), r * Math.sin(golden * i), z]);
  }
  return out;
}

const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
function normalised(a) {
  const l = Math.hypot(a[0], a[1], a[2]);
  return l > 0 ? [a[0] / l, a[1] / l, a[2] / l] : null;
}

/// positions: Float32Array 3·#V, indices: Uint32Array 3·#F; point, normal, preferred: [x, y, z]
/// (normal and preferred unit vectors). Returns { direction: [x, y, z], distance }.
export function clearView(positions, indices, point, normal, preferred, distance) {
  // Triangles that can block: bounding box within `distance` of the point.
  const near = [];
  const faces = indices.length / 3;
  for (let f = 0; f < faces; ++f) {
    let inside = true;
    for (let k = 0; k < 3 && inside; ++k) {
      let lo = Infinity, hi = -Infinity;
      for (let c = 0; c < 3; ++c) {
        const x = positions[3 * indices[3 * f + c] + k];
        if (x < lo) lo = x;
        if (x > hi) hi = x;
      }
      inside = lo <= point[k] + distance && hi >= point[k] - distance;
    }
    if (inside) near.push(f);
  }
  const mixes = [0.8, 0.6, 0.4].map((w) => normalised(normal.map((x, k) => w * x + (1 - w) * preferred[k])));
  const spread = Math.max(8, Math.min(latticeSize, Math.floor(testBudget / Math.max(near.length, 1)) - 4));
  const candidates = [normal, ...mixes, ...lattice(spread)].filter((d) => d && dot(d, normal) > 0.1);

  // The segment starts a little off the surface, so the point's own faces do not block it.
  const eps = 1e-4 * distance;
  const origin = point.map((x, k) => x + eps * normal[k]);
  const score = (d) => dot(d, normal) + 0.5 * dot(d, preferred);
  candidates.sort((a, b) => score(b) - score(a));
  let fallback = null;
  for (const d of candidates) {
    const hit = firstHit(positions, indices, near, origin, d, distance);
    if (hit === Infinity) return { direction: d, distance };
    if (!fallback || hit > fallback.hit) fallback = { direction: d, hit };
  }
  if (fallback) return { direction: fallback.direction, distance: 0.8 * fallback.hit };
  return { direction: normal, distance };
}

/// Distance along the ray o + t·d (0 < t < limit) to the first triangle of `faces`, or
/// Infinity.
function firstHit(p, index, faces, o, d, limit) {
  let nearest = Infinity;
  for (const f of faces) {
    const a = 3 * index[3 * f], b = 3 * index[3 * f + 1], c = 3 * index[3 * f + 2];
    const e1x = p[b] - p[a], e1y = p[b + 1] - p[a + 1], e1z = p[b + 2] - p[a + 2];
    const e2x = p[c] - p[a], e2y = p[c + 1] - p[a + 1], e2z = p[c + 2] - p[a + 2];
    const hx = d[1] * e2z - d[2] * e2y, hy = d[2] * e2x - d[0] * e2z, hz = d[0] * e2y - d[1] * e2x;
    const det = e1x * hx + e1y * hy + e1z * hz;
    if (Math.abs(det) < 1e-20) continue;
    const inv = 1 / det;
    const sx = o[0] - p[a], sy = o[1] - p[a + 1], sz = o[2] - p[a + 2];
    const u = inv * (sx * hx + sy * hy + sz * hz);
    if (u < 0 || u > 1) continue;
    const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
    const v = inv * (d[0] * qx + d[1] * qy + d[2] * qz);
    if (v < 0 || u + v > 1) continue;
    const t = inv * (e2x * qx + e2y * qy + e2z * qz);
    if (t > 0 && t < limit && t < nearest) nearest = t;
  }
  return nearest;
}
