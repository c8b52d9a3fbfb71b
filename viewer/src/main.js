// Streams a COPC file by screen-space error: a node is drawn while its box is in view, and its
// children are fetched (HTTP range requests) while its points' spacing, spacing / 2^depth, covers more
// than MAX_GAP_PX pixels on screen, the coarsest gaps first, until the drawn points would pass the
// point budget. Nodes out of view stay loaded up to a cache of points, the least recently drawn
// unloaded first. A hierarchy page below the root page is read when the refinement first reaches its
// subtree. With geodesic-lod's files every depth cut drawn is one of its nested LODs.
// window.viewerState reports what was loaded, for people and for the tests.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { Copc } from 'copc';
import { createLazPerf } from 'laz-perf';

const MAX_GAP_PX = 6;        // refine a node while its point spacing spans more pixels than this
const MAX_IN_FLIGHT = 4;     // node requests at once
const BACKGROUND = 0x101418;

const query = new URLSearchParams(location.search);
const file = query.get('file') || 'data.copc.laz';
// Points drawn at most (?budget=), and points kept loaded at most (?cache=) besides those drawn: a
// few million points is what a laptop's GPU draws smoothly; the cache spares fetching nodes again
// when the camera comes back.
const POINT_BUDGET = Number(query.get('budget')) || 4_000_000;
const CACHE_POINTS = Number(query.get('cache')) || 2 * POINT_BUDGET;
const state = (window.viewerState = {
  file, ready: false, busy: 0, requests: 0, pages: 0, loadedNodes: 0, loadedPoints: 0, unloadedNodes: 0, drawnNodes: 0,
  drawnPoints: 0, maxDepth: -1, budget: POINT_BUDGET, cache: CACHE_POINTS, errors: [],
});
const fail = (what) => { state.errors.push(String(what)); status(`error: ${what}`); };
window.addEventListener('error', (e) => fail(e.message));
window.addEventListener('unhandledrejection', (e) => fail(e.reason));

function status(text) { document.getElementById('status').textContent = text; }

async function getter(begin, end) {
  state.requests++;
  const r = await fetch(file, { headers: { Range: `bytes=${begin}-${end - 1}` } });
  if (r.status !== 206) throw new Error(`${file}: range request answered with HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}

function colours(view, count, zOf, zRange) {
  const rgb = new Float32Array(3 * count);
  const has = (n) => view.dimensions[n] !== undefined;
  if (has('Red') && has('Green') && has('Blue')) {
    const [r, g, b] = ['Red', 'Green', 'Blue'].map((n) => view.getter(n));
    let top = 0;
    for (let i = 0; i < count; i++) top = Math.max(top, r(i), g(i), b(i));
    const scale = top > 255 ? 65535 : 255;
    if (top > 0) {
      for (let i = 0; i < count; i++) rgb.set([r(i) / scale, g(i) / scale, b(i) / scale], 3 * i);
      return rgb;
    }
  }
  const c = new THREE.Color();
  for (let i = 0; i < count; i++) {  // by height: blue low, yellow high
    const t = (zOf(i) - zRange[0]) / Math.max(zRange[1] - zRange[0], 1e-9);
    c.setHSL(0.66 - 0.5 * Math.min(Math.max(t, 0), 1), 0.8, 0.5);
    rgb.set([c.r, c.g, c.b], 3 * i);
  }
  return rgb;
}

async function main() {
  const lazPerf = await createLazPerf({ locateFile: (f) => new URL(f, location.href).href });
  const copc = await Copc.create(getter);
  const { nodes, pages } = await Copc.loadHierarchyPage(getter, copc.info.rootHierarchyPage);
  state.pages = 1;
  const [x0, y0, z0, x1, y1, z1] = copc.info.cube;
  const centre = new THREE.Vector3((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2);
  const side = x1 - x0;
  const zRange = [copc.header.min[2], copc.header.max[2]];

  const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(innerWidth, innerHeight);
  document.body.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(BACKGROUND);
  const camera = new THREE.PerspectiveCamera(50, innerWidth / innerHeight, side * 1e-4, side * 20);
  camera.up.set(0, 0, 1);
  const extent = new THREE.Vector3(copc.header.max[0] - copc.header.min[0], copc.header.max[1] - copc.header.min[1],
                                   copc.header.max[2] - copc.header.min[2]);
  const middle = new THREE.Vector3(...copc.header.min).add(extent.clone().multiplyScalar(0.5)).sub(centre);
  // Stand off the points' box by its diagonal, or by the cube's side where the points have no extent (one
  // point, or all at one position): a camera on its target sees nothing.
  const standOff = 0.8 * (extent.length() || side);
  camera.position.copy(middle).add(new THREE.Vector3(0, -1, 0.8).multiplyScalar(standOff));
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(middle);
  controls.update();
  const material = new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, vertexColors: true });

  const loaded = new Map();   // key -> THREE.Points (or null while loading, or for a node without points)
  const boxOf = (d, x, y, z) => {
    const s = side / 2 ** d;
    const min = new THREE.Vector3(x0 + x * s, y0 + y * s, z0 + z * s).sub(centre);
    return new THREE.Box3(min, min.clone().addScalar(s));
  };

  // The nodes to draw: in view, each refined while its gap on screen is above MAX_GAP_PX, the
  // largest gap first, as long as its points fit in the budget (the root always).
  function wanted() {
    const frustum = new THREE.Frustum().setFromProjectionMatrix(
      new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse));
    const pixels = innerHeight / (2 * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2));
    const out = [];
    let points = 0;
    const queue = [{ key: '0-0-0-0', gap: Infinity }];  // sorted by gap, largest last
    while (queue.length) {
      const { key } = queue.pop();
      const node = nodes[key];
      if (!node) {
        if (pages[key]) loadPage(key);
        continue;
      }
      const [d, x, y, z] = key.split('-').map(Number);
      const box = boxOf(d, x, y, z);
      if (!frustum.intersectsBox(box)) continue;
      if (out.length > 0 && points + node.pointCount > POINT_BUDGET) continue;
      out.push(key);
      points += node.pointCount;
      const distance = Math.max(box.distanceToPoint(camera.position), side * 1e-6);
      const gap = (copc.info.spacing / 2 ** d) / distance * pixels;
      if (gap > MAX_GAP_PX) {
        for (let c = 0; c < 8; c++) {
          queue.push({ key: `${d + 1}-${2 * x + (c & 1)}-${2 * y + ((c >> 1) & 1)}-${2 * z + (c >> 2)}`, gap });
        }
        queue.sort((a, b) => a.gap - b.gap);
      }
    }
    return out;
  }

  // Unloads the nodes not drawn, least recently drawn first, until the loaded points fit the cache
  // (or only drawn nodes are left).
  const lastDrawn = new Map();  // key -> frame number
  let frameNumber = 0;
  function unload(want) {
    const idle = [...loaded].filter(([key, points]) => points && !want.has(key))
      .sort(([a], [b]) => (lastDrawn.get(a) || 0) - (lastDrawn.get(b) || 0));
    for (const [key, points] of idle) {
      if (state.loadedPoints <= CACHE_POINTS) break;
      scene.remove(points);
      points.geometry.dispose();
      loaded.delete(key);
      state.loadedPoints -= points.userData.count;
      state.unloadedNodes++;
    }
  }

  // Reads the hierarchy page of the subtree at `key` (once), then looks at the view again.
  const pagesLoading = new Set();
  async function loadPage(key) {
    if (pagesLoading.has(key)) return;
    pagesLoading.add(key);
    state.busy++;
    try {
      const page = await Copc.loadHierarchyPage(getter, pages[key]);
      Object.assign(nodes, page.nodes);
      Object.assign(pages, page.pages);
      delete pages[key];
      state.pages++;
    } catch (e) {
      fail(`hierarchy page ${key}: ${e.message || e}`);
    } finally {
      state.busy--;
      frame();
    }
  }

  async function load(key) {
    loaded.set(key, null);
    state.busy++;
    try {
      const node = nodes[key];
      if (node.pointCount > 0) {
        const view = await Copc.loadPointDataView(getter, copc, node, { lazPerf });
        const [gx, gy, gz] = ['X', 'Y', 'Z'].map((n) => view.getter(n));
        const pos = new Float32Array(3 * view.pointCount);
        for (let i = 0; i < view.pointCount; i++) {
          pos[3 * i] = gx(i) - centre.x;
          pos[3 * i + 1] = gy(i) - centre.y;
          pos[3 * i + 2] = gz(i) - centre.z;
        }
        const geometry = new THREE.BufferGeometry();
        geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
        geometry.setAttribute('color', new THREE.BufferAttribute(colours(view, view.pointCount, gz, zRange), 3));
        const points = new THREE.Points(geometry, material);
        points.userData = { depth: Number(key.split('-')[0]), count: view.pointCount };
        scene.add(points);
        loaded.set(key, points);
        state.loadedPoints += view.pointCount;
      }
      state.loadedNodes++;
    } catch (e) {
      fail(`${key}: ${e.message || e}`);
    } finally {
      state.busy--;
    }
  }

  function update() {
    const keys = wanted();
    const want = new Set(keys);
    frameNumber++;
    unload(want);
    let drawnNodes = 0, drawnPoints = 0;
    for (const [key, points] of loaded) {
      if (!points) continue;
      points.visible = want.has(key);
      if (points.visible) {
        lastDrawn.set(key, frameNumber);
        drawnNodes++;
        drawnPoints += points.userData.count;
        state.maxDepth = Math.max(state.maxDepth, points.userData.depth);
      }
    }
    Object.assign(state, { drawnNodes, drawnPoints });
    const missing = keys.filter((k) => !loaded.has(k)).sort((a, b) => Number(a.split('-')[0]) - Number(b.split('-')[0]));
    for (const key of missing.slice(0, Math.max(0, MAX_IN_FLIGHT - state.busy))) load(key).then(frame);
    state.ready = missing.length === 0 && state.busy === 0;
    status(`${file}: ${drawnPoints.toLocaleString()} points in ${drawnNodes} nodes, depth ${state.maxDepth}` +
           (state.ready ? '' : ' (loading)'));
    renderer.render(scene, camera);
  }
  let queued = false;
  function frame() {
    if (queued) return;
    queued = true;
    requestAnimationFrame(() => { queued = false; update(); });
  }
  controls.addEventListener('change', frame);
  addEventListener('resize', () => {
    camera.aspect = innerWidth / innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(innerWidth, innerHeight);
    frame();
  });
  window.viewer = {
    // Moves the camera towards its target, to `fraction` of the distance (a wheel zoom does the same).
    zoom(fraction) {
      camera.position.sub(controls.target).multiplyScalar(fraction).add(controls.target);
      controls.update();
      frame();
    },
  };
  frame();
}

main().catch(fail);
