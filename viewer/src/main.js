// bemshape's HTML thickness report: the surface coloured by thickness (three.js, orbit/zoom
// with OrbitControls), and the panel (panel.js). Clicking a region flies the camera to its
// extreme value, marks it with a sphere and highlights and outlines the region's faces.
//
// window.bemshapeViewer is the page's state for scripts and tests: { ready, error,
// timings: { decode, build, select (the last region's highlight and line of sight):
// durations [ms]; firstRender: ms from navigation start to the first picture drawn },
// selectRegion(i), resetView(), selected, flying, defectFaces (faces drawn in the defect
// colour) }.

import {
  AmbientLight, BufferAttribute, BufferGeometry, Color, DirectionalLight, DoubleSide,
  LineBasicMaterial, LineSegments, LinearSRGBColorSpace, Mesh, MeshBasicMaterial,
  MeshLambertMaterial, PerspectiveCamera, Scene, SphereGeometry, Vector3, WebGLRenderer,
  ColorManagement, BackSide,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

import { colourValues } from './colour_map.js';
import { fillColourBar, fillDefects, fillHeader, fillHistogram, fillRegions } from './panel.js';
import { readReport } from './report_data.js';
import { clearView } from './view_direction.js';

const pick = 0xff2d55;
const flightMs = 700;

const state = { ready: false, error: null, timings: {}, selected: -1, flying: false };
window.bemshapeViewer = state;

function fail(error) {
  state.error = String(error && error.message ? error.message : error);
  const status = document.getElementById('status');
  status.className = 'error';
  status.textContent = `The report cannot be shown: ${state.error}`;
  throw error;
}

/// Faces above which the surface is drawn without multisampling: software WebGL
/// (SwiftShader) then draws a 10⁶-face surface in a fraction of the time, and at such
/// densities the triangles are smaller than pixels anyway.
const antialiasFaceLimit = 300000;

function webglRenderer(canvasParent, faces) {
  let renderer;
  try {
    renderer = new WebGLRenderer({ antialias: faces <= antialiasFaceLimit, preserveDrawingBuffer: true });
  } catch (error) {
    throw new Error(`this browser gives no WebGL context (${error.message}); open the file in a browser with WebGL enabled`);
  }
  renderer.outputColorSpace = LinearSRGBColorSpace;
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  canvasParent.prepend(renderer.domElement);
  return renderer;
}

/// Edges used by exactly one of the given faces: the region's outline, as pairs of vertex
/// indices.
function boundaryEdges(indices, faces) {
  const count = new Map();
  for (const f of faces) {
    for (let k = 0; k < 3; ++k) {
      const a = indices[3 * f + k], b = indices[3 * f + ((k + 1) % 3)];
      const key = a < b ? a * 4294967296 + b : b * 4294967296 + a;
      count.set(key, (count.get(key) || 0) + 1);
    }
  }
  const out = [];
  for (const [key, n] of count)
    if (n === 1) out.push(Math.floor(key / 4294967296), key % 4294967296);
  return Uint32Array.from(out);
}

function faceNormal(positions, indices, f) {
  const p = [0, 1, 2].map((k) => new Vector3().fromArray(positions, 3 * indices[3 * f + k]));
  return p[1].sub(p[0]).cross(p[2].sub(p[0])).normalize();
}

function faceCentroid(positions, indices, f) {
  const c = new Vector3();
  for (let k = 0; k < 3; ++k) c.add(new Vector3().fromArray(positions, 3 * indices[3 * f + k]));
  return c.multiplyScalar(1 / 3);
}

function easeInOut(t) {
  return t < 0.5 ? 4 * t * t * t : 1 - Math.pow(-2 * t + 2, 3) / 2;
}

function start() {
  const t0 = performance.now();
  const report = readReport();
  const { meta, positions, indices } = report;
  state.timings.decode = performance.now() - t0;
  fillHeader(meta);
  fillColourBar(meta);
  fillHistogram(meta);
  fillDefects(meta);

  const view = document.getElementById('view');
  const renderer = webglRenderer(view, meta.faces);
  ColorManagement.enabled = false;  // the colours are the colour bar's sRGB values as they are
  const scene = new Scene();
  scene.background = new Color(0xeef1f4);

  // The surface: indexed geometry coloured per vertex, or per face on a non-indexed copy.
  const geometry = new BufferGeometry();
  const positionAttribute = new BufferAttribute(positions, 3);
  geometry.setAttribute('position', positionAttribute);
  geometry.setIndex(new BufferAttribute(indices, 1));
  const [lo, hi] = meta.colour_range;
  let faceGeometry = null;
  const material = new MeshLambertMaterial({ vertexColors: true, flatShading: true, side: DoubleSide });
  const surface = new Mesh(geometry, material);
  const colourBy = (perFace) => {
    if (perFace) {
      if (!faceGeometry) {
        faceGeometry = geometry.toNonIndexed();
        faceGeometry.deleteAttribute('color');
        const faceColours = colourValues(report.faceValues, lo, hi, new Uint8Array(3 * meta.faces));
        const colours = new Uint8Array(9 * meta.faces);
        for (let f = 0; f < meta.faces; ++f)
          for (let k = 0; k < 3; ++k) colours.set(faceColours.subarray(3 * f, 3 * f + 3), 9 * f + 3 * k);
        faceGeometry.setAttribute('color', new BufferAttribute(colours, 3, true));
      }
      surface.geometry = faceGeometry;
    } else {
      surface.geometry = geometry;
    }
  };
  if (report.vertexValues) {
    const colours = colourValues(report.vertexValues, lo, hi, new Uint8Array(3 * meta.vertices));
    geometry.setAttribute('color', new BufferAttribute(colours, 3, true));
  }
  colourBy(!report.vertexValues);
  if (report.vertexValues && report.faceValues) {
    document.getElementById('face-mode-label').hidden = false;
    document.getElementById('face-mode').addEventListener('change', (event) => {
      colourBy(event.target.checked);
      render();
    });
  }
  scene.add(surface);
  // Faces near a defect region, always drawn over the thickness in the defect colour.
  if (report.defectFaces.length > 0) {
    const defectIndices = new Uint32Array(3 * report.defectFaces.length);
    report.defectFaces.forEach((f, k) => defectIndices.set(indices.subarray(3 * f, 3 * f + 3), 3 * k));
    const defectGeometry = new BufferGeometry();
    defectGeometry.setAttribute('position', positionAttribute);
    defectGeometry.setIndex(new BufferAttribute(defectIndices, 1));
    const [r, g, b] = meta.defect_colour.map((c) => c / 255);
    const defects = new Mesh(defectGeometry, new MeshBasicMaterial({
      color: new Color(r, g, b), transparent: true, opacity: 0.75, depthWrite: false, side: DoubleSide,
      polygonOffset: true, polygonOffsetFactor: -1, polygonOffsetUnits: -1 }));
    defects.renderOrder = 1;
    defects.name = 'defects';
    scene.add(defects);
  }
  state.defectFaces = report.defectFaces.length;
  geometry.computeBoundingSphere();
  geometry.computeBoundingBox();
  const radius = Math.max(geometry.boundingSphere.radius, 1e-12);
  const centre = geometry.boundingSphere.center.clone();

  // Camera with a headlight; z up, as CAD parts are usually modelled.
  const camera = new PerspectiveCamera(35, 1, radius * 1e-3, radius * 100);
  camera.up.set(0, 0, 1);
  scene.add(camera);
  scene.add(new AmbientLight(0xffffff, 1.7));
  const headlight = new DirectionalLight(0xffffff, 1.6);
  headlight.position.set(0.3, 0.5, 1);
  camera.add(headlight);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;
  controls.screenSpacePanning = true;

  // Highlight of the selected region (its faces, over the surface), its outline, the marker.
  const highlight = new Mesh(
    new BufferGeometry(),
    new MeshBasicMaterial({ color: pick, transparent: true, opacity: 0.35, depthWrite: false, side: DoubleSide,
                            polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -2 }));
  highlight.geometry.setAttribute('position', positionAttribute);
  highlight.renderOrder = 1;
  const outline = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ color: pick }));
  outline.geometry.setAttribute('position', positionAttribute);
  outline.renderOrder = 2;
  const marker = new Mesh(new SphereGeometry(1, 24, 16),
                          new MeshBasicMaterial({ color: pick, depthTest: false, transparent: true }));
  const halo = new Mesh(new SphereGeometry(1.35, 24, 16),
                        new MeshBasicMaterial({ color: 0xffffff, depthTest: false, transparent: true, side: BackSide }));
  marker.renderOrder = 11;
  halo.renderOrder = 10;
  marker.add(halo);
  marker.name = 'marker';
  for (const object of [highlight, outline, marker]) {
    object.visible = false;
    scene.add(object);
  }

  const render = () => renderer.render(scene, camera);
  controls.addEventListener('change', render);

  let size = '';
  const resize = () => {
    const w = Math.max(view.clientWidth, 1), h = Math.max(view.clientHeight, 1);
    if (`${w}x${h}` === size) return;
    size = `${w}x${h}`;
    renderer.setSize(w, h, false);
    renderer.domElement.style.width = '100%';
    renderer.domElement.style.height = '100%';
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    render();
  };
  new ResizeObserver(resize).observe(view);

  /// Distance at which a sphere of radius r fills the smaller side of the view.
  const fitDistance = (r) => {
    const vertical = (camera.fov * Math.PI) / 360;
    const horizontal = Math.atan(Math.tan(vertical) * camera.aspect);
    return (1.02 * r) / Math.sin(Math.min(vertical, horizontal));
  };

  let flight = null;
  const flyTo = (target, position) => {
    const from = { target: controls.target.clone(), position: camera.position.clone() };
    const began = performance.now();
    state.flying = true;
    flight = (now) => {
      const t = Math.min((now - began) / flightMs, 1);
      const s = easeInOut(t);
      controls.target.lerpVectors(from.target, target, s);
      camera.position.lerpVectors(from.position, position, s);
      controls.update();
      render();
      if (t < 1) requestAnimationFrame(flight);
      else state.flying = false;
    };
    requestAnimationFrame(flight);
  };

  const overviewDirection = new Vector3(0.55, -1, 0.8).normalize();
  state.resetView = (animate = true) => {
    const position = centre.clone().addScaledVector(overviewDirection, fitDistance(radius));
    if (animate) flyTo(centre.clone(), position);
    else {
      controls.target.copy(centre);
      camera.position.copy(position);
      controls.update();
    }
  };
  document.getElementById('reset-view').addEventListener('click', () => state.resetView());

  const origin = new Vector3().fromArray(meta.origin);
  const buttons = fillRegions(meta, (i) => state.selectRegion(i));
  state.selectRegion = (i) => {
    const region = meta.regions[i];
    if (!region) throw new Error(`no region ${i}: the report has ${meta.regions.length}`);
    const began = performance.now();
    state.selected = i;
    buttons.forEach((b, k) => b.classList.toggle('selected', k === i));
    const faces = report.regionFaces.subarray(region.face_offset, region.face_offset + region.face_count);
    const regionIndices = new Uint32Array(3 * faces.length);
    for (let k = 0; k < faces.length; ++k) regionIndices.set(indices.subarray(3 * faces[k], 3 * faces[k] + 3), 3 * k);
    highlight.geometry.setIndex(new BufferAttribute(regionIndices, 1));
    outline.geometry.setIndex(new BufferAttribute(boundaryEdges(indices, faces), 1));
    highlight.visible = outline.visible = true;

    // Look at the extreme from outside, near the outward normal of the region's face nearest
    // to it and towards the current view, along a line of sight the surface does not block
    // (view_direction.js).
    const extreme = new Vector3().fromArray(region.extreme_location).sub(origin);
    let nearest = -1, best = Infinity;
    for (const f of faces) {
      const d = faceCentroid(positions, indices, f).distanceToSquared(extreme);
      if (d < best) { best = d; nearest = f; }
    }
    const current = camera.position.clone().sub(controls.target).normalize();
    const normal = nearest >= 0 ? faceNormal(positions, indices, nearest) : current.clone();
    const boxMin = new Vector3().fromArray(region.box_min), boxMax = new Vector3().fromArray(region.box_max);
    const regionRadius = 0.5 * boxMin.distanceTo(boxMax);
    const viewRadius = Math.min(Math.max(regionRadius, 0.12 * radius), radius);
    const sight = clearView(positions, indices, extreme.toArray(), normal.toArray(), current.toArray(),
                           fitDistance(viewRadius));
    marker.scale.setScalar(0.025 * viewRadius);
    marker.position.copy(extreme);
    marker.visible = true;
    state.timings.select = performance.now() - began;
    flyTo(extreme, extreme.clone().addScaledVector(new Vector3().fromArray(sight.direction), sight.distance));
  };

  state.timings.build = performance.now() - t0 - state.timings.decode;
  state.resetView(false);
  resize();
  // WebGL runs asynchronously: reading one pixel back waits until the first picture is
  // drawn, so that firstRender is when it exists, not when it was asked for.
  const gl = renderer.getContext();
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
  state.timings.firstRender = performance.now();
  document.getElementById('status').remove();
  state.ready = true;
  document.body.dataset.state = 'ready';
}

try {
  start();
} catch (error) {
  fail(error);
}
