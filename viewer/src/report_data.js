// Reads the report that apps/output/html_report.cpp embeds in the page: one JSON element with
// every small field, and the arrays as base64 of little-endian float32/uint32 in text elements
// (the layout is documented in apps/output/html_report.hpp).

const littleEndian = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;

/// The bytes of element #bemshape-<name> (null if the page has none); the element's text is
/// dropped afterwards so that the base64 does not stay in memory beside the arrays.
function bytesOf(name) {
  const element = document.getElementById('bemshape-' + name);
  if (!element) return null;
  const text = element.textContent;
  element.textContent = '';
  if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(text);
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

function typed(name, Type) {
  const bytes = bytesOf(name);
  if (bytes === null) return null;
  if (bytes.byteLength % 4 !== 0) throw new Error(`bemshape-${name}: ${bytes.byteLength} bytes is not a whole number of 4-byte values`);
  if (littleEndian) return new Type(bytes.buffer, bytes.byteOffset, bytes.byteLength / 4);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const out = new Type(bytes.byteLength / 4);
  const get = Type === Float32Array ? (i) => view.getFloat32(4 * i, true) : (i) => view.getUint32(4 * i, true);
  for (let i = 0; i < out.length; ++i) out[i] = get(i);
  return out;
}

/// { meta, positions (Float32Array 3·#V, relative to meta.origin), indices (Uint32Array 3·#F),
///   vertexValues, faceValues (Float32Array or null), regionFaces, defectFaces (Uint32Array) }
export function readReport() {
  const element = document.getElementById('bemshape-report');
  if (!element) throw new Error('this page holds no bemshape report data');
  const meta = JSON.parse(element.textContent);
  const report = {
    meta,
    positions: typed('positions', Float32Array),
    indices: typed('indices', Uint32Array),
    vertexValues: meta.has_vertex_values ? typed('vertex-values', Float32Array) : null,
    faceValues: meta.has_face_values ? typed('face-values', Float32Array) : null,
    regionFaces: typed('region-faces', Uint32Array) ?? new Uint32Array(0),
    defectFaces: typed('defect-faces', Uint32Array) ?? new Uint32Array(0),
  };
  if (report.defectFaces.length !== (meta.defect_face_count ?? 0))
    throw new Error(`the report lists ${meta.defect_face_count} defect faces but holds ${report.defectFaces.length}`);
  if (report.positions.length !== 3 * meta.vertices || report.indices.length !== 3 * meta.faces)
    throw new Error(`the report's arrays do not match its ${meta.vertices} vertices and ${meta.faces} faces`);
  return report;
}
