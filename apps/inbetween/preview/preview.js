// The page script of `inbetween view` (docs/preview.md).  Bundled with three.js by esbuild at build
// time into one classic script that the tool inlines into the HTML file (nothing is fetched when
// the page opens; it works from file://).
//
// It plays the baked values that the tool embedded (window.INBETWEEN_DATA, written by
// apps/inbetween/preview.cpp from Scene::sample with round-trip precision): positions, rotations,
// scales, camera poses and the distance/speed columns are read from the table, never recomputed.
// The only arithmetic here is drawing: axes, path polylines the tool sampled, 2-D plot scaling,
// and bones: a segment between two baked world positions (parent and child), copied each frame.
import {
  AxesHelper,
  BoxGeometry,
  BufferGeometry,
  CameraHelper,
  Color,
  ConeGeometry,
  Float32BufferAttribute,
  GridHelper,
  Group,
  Line,
  LineBasicMaterial,
  LineSegments,
  Mesh,
  MeshStandardMaterial,
  AmbientLight,
  DirectionalLight,
  PerspectiveCamera,
  Scene,
  SphereGeometry,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const data = window.INBETWEEN_DATA;
const palette = [0xe4572e, 0x17bebb, 0xffc914, 0x76b041, 0x8e6c8a, 0x2e86ab, 0xf18f01, 0xc73e1d];

// ------------------------------------------------------------------------------------- the table
const columnIndex = new Map(data.columns.map((name, i) => [name, i]));
const column = (name) => (columnIndex.has(name) ? columnIndex.get(name) : -1);
const frameCount = data.frames.length;

// ------------------------------------------------------------------------------------ hierarchy
// A skeleton is objects in a hierarchy: every object with a parent gets a bone, the segment from
// its parent's world position to its own.  A plain object (not a camera, not on a path) with a
// plain parent or a plain child is a joint, drawn as a small sphere.  In a scene of more than
// kManyObjects objects (a character), only roots draw their trails and only the first
// kManyObjects objects have their own line in the legend and their local axes drawn.
const kManyObjects = 12;
const many = data.objects.length > kManyObjects;
const plain = (i) => data.objects[i].kind === 'object';
const hasPlainChildren = new Set(data.objects.map((o, i) => i).filter((i) => plain(i) && data.objects[i].parent !== null).map((i) => data.objects[i].parent));
const isJoint = (object, i) => plain(i) && ((object.parent !== null && plain(object.parent)) || hasPlainChildren.has(i));
const boneChildren = data.objects.map((o, i) => i).filter((i) => data.objects[i].parent !== null);

// --------------------------------------------------------------------------------------- 3-D view
const view = document.getElementById('view');
const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.setClearColor(0x1d2024);
view.appendChild(renderer.domElement);

const scene = new Scene();
scene.add(new AmbientLight(0xffffff, 0.9));
const sun = new DirectionalLight(0xffffff, 1.6);
sun.position.set(3, 10, 6);
scene.add(sun);

// Scene extent from every baked position and path point: sizes the shapes, grid and free camera.
const lo = new Vector3(Infinity, Infinity, Infinity);
const hi = new Vector3(-Infinity, -Infinity, -Infinity);
for (const object of data.objects) {
  const c = column(object.name + '.translation.x');
  for (const row of data.rows) {
    lo.min(new Vector3(row[c], row[c + 1], row[c + 2]));
    hi.max(new Vector3(row[c], row[c + 1], row[c + 2]));
  }
  for (const leg of object.path_points || []) for (const p of leg) {
    lo.min(new Vector3(p[0], p[1], p[2]));
    hi.max(new Vector3(p[0], p[1], p[2]));
  }
}
const centre = lo.clone().add(hi).multiplyScalar(0.5);
const extent = Math.max(hi.clone().sub(lo).length(), 1);
const shapeSize = extent * 0.03;
// Joints: a sphere a tenth of the median bone length at the first frame (bones of a character are
// much shorter than the extent of its trail), at most a shape.
let jointRadius = shapeSize * 0.35;
if (boneChildren.length > 0) {
  const row = data.rows[0];
  const lengths = boneChildren.map((i) => {
    const c = column(data.objects[i].name + '.translation.x'), p = column(data.objects[data.objects[i].parent].name + '.translation.x');
    return Math.hypot(row[c] - row[p], row[c + 1] - row[p + 1], row[c + 2] - row[p + 2]);
  }).filter((l) => l > 0).sort((a, b) => a - b);
  if (lengths.length > 0) jointRadius = Math.min(jointRadius, lengths[lengths.length >> 1] * 0.1);
}

const grid = new GridHelper(Math.ceil(extent * 1.5), 20, 0x555a60, 0x33373c);
grid.position.set(centre.x, lo.y, centre.z);
scene.add(grid);
scene.add(new AxesHelper(shapeSize * 3));

// One entry per object: the group whose world pose is set from the table every frame.
const shown = new Map();
const cameras = [];
data.objects.forEach((object, i) => {
  const colour = new Color(palette[i % palette.length]);
  const group = new Group();
  group.name = object.name;
  group.matrixAutoUpdate = true;
  const base = column(object.name + '.translation.x');
  const entry = { object, group, t: base, r: column(object.name + '.rotation.w'), s: column(object.name + '.scale.x') };
  if (object.kind === 'camera') {
    // A frustum (three.js's CameraHelper) of the scene camera's field of view, short, for the
    // free view; the camera looked through is a second PerspectiveCamera with the same pose.
    const frustum = new PerspectiveCamera(object.yfov_deg, 16 / 9, shapeSize * 0.5, shapeSize * 4);
    group.add(frustum);
    const helper = new CameraHelper(frustum);
    helper.setColors(colour, colour, new Color(0x66ccff), new Color(0xffffff), new Color(0x777777));  // frustum, cone, up, target, cross
    scene.add(helper);
    entry.helper = helper;
    entry.lens = new PerspectiveCamera(object.yfov_deg, 16 / 9, extent * 0.002, extent * 20);
    cameras.push(object.name);
  } else if (isJoint(object, i)) {
    // A joint: a sphere, a root's larger.
    const radius = object.parent === null ? jointRadius * 1.6 : jointRadius;
    group.add(new Mesh(new SphereGeometry(radius, 12, 8), new MeshStandardMaterial({ color: colour, roughness: 0.55 })));
  } else {
    const material = new MeshStandardMaterial({ color: colour, roughness: 0.55 });
    const body = object.kind === 'path'
      ? new Mesh(new ConeGeometry(shapeSize * 0.7, shapeSize * 2.2, 16).rotateX(Math.PI / 2), material)  // points along +Z, the path front
      : new Mesh(new BoxGeometry(shapeSize * 1.4, shapeSize * 1.4, shapeSize * 1.4), material);
    group.add(body);
  }
  if (!many || object.kind !== 'object') group.add(new AxesHelper(isJoint(object, i) ? jointRadius * 4 : shapeSize * 2.5));
  scene.add(group);

  // The path legs, sampled by the tool in the parent's space: a line under a group that follows
  // the parent's baked world pose.
  if (object.path_points) {
    const space = new Group();
    for (const leg of object.path_points) {
      const geometry = new BufferGeometry();
      geometry.setAttribute('position', new Float32BufferAttribute(leg.flat(), 3));
      space.add(new Line(geometry, new LineBasicMaterial({ color: colour })));
    }
    scene.add(space);
    entry.pathSpace = space;
  }
  // An object that moves but is not on a path (keyed, or a glTF node): its trajectory, the baked
  // world positions of every frame, as a dim line; in a scene of many objects, for roots only
  // (a character's trail is its root's).
  let trajectory = false;
  if (!object.path_points && (!many || object.parent === null)) {
    const points = data.rows.map((row) => [row[base], row[base + 1], row[base + 2]]);
    trajectory = points.some((p) => p[0] !== points[0][0] || p[1] !== points[0][1] || p[2] !== points[0][2]);
    if (trajectory) {
      const geometry = new BufferGeometry();
      geometry.setAttribute('position', new Float32BufferAttribute(points.flat(), 3));
      scene.add(new Line(geometry, new LineBasicMaterial({ color: colour, transparent: true, opacity: 0.45 })));
    }
  }
  entry.trajectory = trajectory;
  shown.set(object.name, entry);
  if (many && i >= kManyObjects) return;

  // Legend entry: the colour of the shape and path line, the name, what it is.
  const item = document.createElement('div');
  const swatch = document.createElement('span');
  swatch.className = 'swatch';
  swatch.style.background = '#' + colour.getHexString();
  const kind = object.kind === 'camera' ? 'camera' : object.kind === 'path' ? 'on a path' : isJoint(object, i) ? (object.parent === null ? 'root' : 'joint') : 'object';
  const line = object.path_points ? ', line: its path' : trajectory ? ', line: its trajectory' : '';
  item.append(swatch, `${object.name} (${kind}${line})`);
  document.getElementById('legend').appendChild(item);
});

if (many) {
  const item = document.createElement('div');
  item.textContent = `… and ${data.objects.length - kManyObjects} more objects (${data.objects.length} in all)`;
  document.getElementById('legend').appendChild(item);
}

// Bones: one line segment per object with a parent, from the parent's displayed world position to
// the object's, rewritten from the groups every frame (applyFrame).
const bonePositions = new Float32Array(boneChildren.length * 6);
const bones = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ color: 0xf2f2f2 }));
bones.geometry.setAttribute('position', new Float32BufferAttribute(bonePositions, 3));
bones.frustumCulled = false;  // its vertices move every frame; the bounding sphere would be stale
if (boneChildren.length > 0) {
  scene.add(bones);
  const item = document.createElement('div');
  const swatch = document.createElement('span');
  swatch.className = 'swatch';
  swatch.style.background = '#f2f2f2';
  item.append(swatch, `bones: ${boneChildren.length} (a line from each object to its parent)`);
  document.getElementById('legend').appendChild(item);
}

// Free camera looking at the whole scene.
const freeCamera = new PerspectiveCamera(45, 16 / 9, extent * 0.002, extent * 50);
freeCamera.position.copy(centre).add(new Vector3(0.45, 0.55, 1.0).multiplyScalar(extent * 0.72));
const controls = new OrbitControls(freeCamera, renderer.domElement);
controls.target.copy(centre);
controls.update();
controls.addEventListener('change', () => render());
let lookThrough = null;  // name of the scene camera looked through, or null for the free camera

// Following a root: the free view keeps its offset from the root's displayed position as the
// frames change (a character walks out of a view that frames its whole trail).  Offered for every
// root with descendants; on by default, for the root with the most, in a scene of many objects.
const rootOf = data.objects.map((o, i) => { let r = i; while (data.objects[r].parent !== null) r = data.objects[r].parent; return r; });
const descendants = data.objects.map(() => 0);
rootOf.forEach((r, i) => { if (r !== i) descendants[r] += 1; });
const followable = data.objects.map((o, i) => i).filter((i) => data.objects[i].parent === null && descendants[i] > 0);
let following = null;  // name of the root followed, or null
function follow(name) {
  if (name !== null && !followable.some((i) => data.objects[i].name === name)) {
    throw new Error(`${name} is not a root with descendants; roots: ${followable.map((i) => data.objects[i].name).join(', ')}`);
  }
  following = name;
  if (name !== null) {
    // Frame the hierarchy as displayed: the view's offset is 2.5 times its largest distance from the root.
    const root = shown.get(name).group.position;
    let size = jointRadius * 10;
    data.objects.forEach((o, i) => { if (rootOf[i] === rootOf[followable.find((k) => data.objects[k].name === name)]) size = Math.max(size, shown.get(o.name).group.position.distanceTo(root)); });
    controls.target.copy(root);
    freeCamera.position.copy(root).add(new Vector3(0.45, 0.35, 1.0).normalize().multiplyScalar(size * 2.5));
  } else {
    controls.target.copy(centre);
    freeCamera.position.copy(centre).add(new Vector3(0.45, 0.55, 1.0).multiplyScalar(extent * 0.72));
  }
  controls.update();
  return following;
}
function keepFollowing() {
  if (following === null) return;
  const delta = shown.get(following).group.position.clone().sub(controls.target);
  if (delta.lengthSq() === 0) return;
  controls.target.add(delta);
  freeCamera.position.add(delta);
  controls.update();
}

function setPose(target, row, entry) {
  target.position.set(row[entry.t], row[entry.t + 1], row[entry.t + 2]);
  target.quaternion.set(row[entry.r + 1], row[entry.r + 2], row[entry.r + 3], row[entry.r]);  // w first in the table
}

let current = 0;  // index into data.frames

function applyFrame(index) {
  const row = data.rows[index];
  for (const entry of shown.values()) {
    setPose(entry.group, row, entry);
    if (entry.s >= 0) entry.group.scale.set(row[entry.s], row[entry.s + 1], row[entry.s + 2]);
    if (entry.lens) setPose(entry.lens, row, entry);
    if (entry.pathSpace) {
      const parent = entry.object.parent === null ? null : shown.get(data.objects[entry.object.parent].name);
      if (parent) {
        setPose(entry.pathSpace, row, parent);
        entry.pathSpace.scale.set(row[parent.s], row[parent.s + 1], row[parent.s + 2]);
      }
    }
  }
  scene.updateMatrixWorld(true);
  for (const entry of shown.values()) if (entry.helper) entry.helper.update();
  const attribute = bones.geometry.getAttribute('position');
  boneChildren.forEach((i, k) => {
    const child = shown.get(data.objects[i].name).group.position, parent = shown.get(data.objects[data.objects[i].parent].name).group.position;
    attribute.setXYZ(2 * k, parent.x, parent.y, parent.z);
    attribute.setXYZ(2 * k + 1, child.x, child.y, child.z);
  });
  attribute.needsUpdate = true;
}

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h, false);
  renderer.domElement.style.width = w + 'px';
  renderer.domElement.style.height = h + 'px';
  freeCamera.aspect = w / h;
  freeCamera.updateProjectionMatrix();
  for (const entry of shown.values()) {
    if (!entry.lens) continue;
    entry.lens.aspect = w / h;
    entry.lens.updateProjectionMatrix();
  }
}

function render() {
  const camera = lookThrough ? shown.get(lookThrough).lens : freeCamera;
  for (const entry of shown.values()) if (entry.helper) entry.helper.visible = entry.object.name !== lookThrough;
  renderer.render(scene, camera);
}

// ------------------------------------------------------------------------------------ speed plots
const plots = document.getElementById('plots');
const pathObjects = data.objects.filter((o) => o.path_points);
const plotRows = [];
for (const object of pathObjects) {
  for (const [what, unit] of [['distance', 'scene units'], ['speed', 'units / s']]) {
    const c = column(object.name + '.' + what);
    if (c < 0) continue;
    const figure = document.createElement('figure');
    const caption = document.createElement('figcaption');
    caption.textContent = `${object.name}: ${what} (${unit}) against frame`;
    const canvas = document.createElement('canvas');
    canvas.width = 360;
    canvas.height = 150;
    figure.append(caption, canvas);
    plots.appendChild(figure);
    plotRows.push({ canvas, c });
  }
}
if (plotRows.length === 0) {
  plots.innerHTML = '<p class="note">No path objects: the speed curves show the distance and speed columns of objects on paths.</p>';
}

// The curve of a plot is drawn once into an off-screen canvas; each frame copies it and marks the
// current frame (long bakes have tens of thousands of rows).
function drawPlot(plot) {
  const { canvas, c } = plot;
  const w = canvas.width, h = canvas.height, left = 46, right = 8, top = 8, bottom = 22;
  if (!plot.background) {
    let vmin = Infinity, vmax = -Infinity;
    for (const row of data.rows) { vmin = Math.min(vmin, row[c]); vmax = Math.max(vmax, row[c]); }
    if (!(vmax > vmin)) { vmax = vmin + 1; }
    const f0 = data.frames[0], f1 = data.frames[frameCount - 1] > f0 ? data.frames[frameCount - 1] : f0 + 1;
    plot.x = (f) => left + (f - f0) / (f1 - f0) * (w - left - right);
    plot.y = (v) => h - bottom - (v - vmin) / (vmax - vmin) * (h - top - bottom);
    const background = document.createElement('canvas');
    background.width = w;
    background.height = h;
    const g = background.getContext('2d');
    g.fillStyle = '#26292e';
    g.fillRect(0, 0, w, h);
    g.strokeStyle = '#555a60';
    g.lineWidth = 1;
    g.strokeRect(left, top, w - left - right, h - top - bottom);
    g.fillStyle = '#aab';
    g.font = '10px sans-serif';
    g.textAlign = 'right';
    g.fillText(vmax.toPrecision(3), left - 4, top + 8);
    g.fillText(vmin.toPrecision(3), left - 4, h - bottom);
    g.textAlign = 'center';
    g.fillText(String(f0), left, h - 6);
    g.fillText(String(f1), w - right, h - 6);
    g.fillText('frame', (left + w - right) / 2, h - 6);
    g.strokeStyle = '#17bebb';
    g.lineWidth = 1.5;
    g.beginPath();
    data.rows.forEach((row, i) => (i ? g.lineTo : g.moveTo).call(g, plot.x(data.frames[i]), plot.y(row[c])));
    g.stroke();
    plot.background = background;
  }
  const g = canvas.getContext('2d');
  g.clearRect(0, 0, w, h);
  g.drawImage(plot.background, 0, 0);
  const fx = plot.x(data.frames[current]);
  g.strokeStyle = '#ffc914';
  g.lineWidth = 1;
  g.beginPath();
  g.moveTo(fx, top);
  g.lineTo(fx, h - bottom);
  g.stroke();
  g.fillStyle = '#ffc914';
  g.beginPath();
  g.arc(fx, plot.y(data.rows[current][c]), 3.5, 0, 2 * Math.PI);
  g.fill();
}

// ------------------------------------------------------------------------------------- timeline
const ui = {
  play: document.getElementById('play'),
  slider: document.getElementById('frame-slider'),
  frame: document.getElementById('frame-number'),
  speed: document.getElementById('speed'),
  loop: document.getElementById('loop'),
  camera: document.getElementById('camera'),
  readout: document.getElementById('readout'),
};
ui.slider.min = 0;
ui.slider.max = frameCount - 1;
ui.slider.step = 1;
for (const name of cameras) {
  const option = document.createElement('option');
  option.value = name;
  option.textContent = 'look through ' + name;
  ui.camera.appendChild(option);
}

function format(v) { return Math.abs(v) < 5e-4 ? '0.000' : v.toFixed(3); }

function show(index) {
  current = Math.max(0, Math.min(frameCount - 1, Math.round(index)));
  applyFrame(current);
  keepFollowing();
  render();
  ui.slider.value = String(current);
  ui.frame.textContent = `frame ${data.frames[current]}  (${(data.frames[current] / data.fps).toFixed(3)} s)`;
  const row = data.rows[current];
  ui.readout.textContent = data.objects.filter((o) => o.kind !== 'camera').slice(0, 4).map((o) => {
    const c = column(o.name + '.translation.x');
    return `${o.name} (${format(row[c])}, ${format(row[c + 1])}, ${format(row[c + 2])})`;
  }).join('   ');
  for (const plot of plotRows) drawPlot(plot);
  return data.frames[current];
}

let playing = false;
let clock = 0;         // frames (fractional) since the first, while playing
let lastTime = null;
function tick(now) {
  if (!playing) return;
  if (lastTime !== null) {
    clock += (now - lastTime) / 1000 * data.fps * Number(ui.speed.value) / data.step;
    if (clock > frameCount - 1) {
      if (ui.loop.checked) clock %= frameCount;
      else { clock = frameCount - 1; setPlaying(false); }
    }
  }
  lastTime = now;
  show(Math.floor(clock));
  if (playing) requestAnimationFrame(tick);
}
function setPlaying(on) {
  playing = on;
  ui.play.textContent = on ? '❚❚ pause' : '▶ play';
  if (on) {
    if (current >= frameCount - 1) current = 0;
    clock = current;
    lastTime = null;
    requestAnimationFrame(tick);
  }
}
ui.play.addEventListener('click', () => setPlaying(!playing));
ui.slider.addEventListener('input', () => { setPlaying(false); show(Number(ui.slider.value)); });
for (const i of followable) {
  const option = document.createElement('option');
  option.value = 'follow:' + data.objects[i].name;
  option.textContent = 'free view following ' + data.objects[i].name;
  ui.camera.insertBefore(option, ui.camera.options[1] || null);
}
ui.camera.addEventListener('change', () => {
  const value = ui.camera.value;
  if (value.startsWith('follow:')) {
    useCamera(null);
    follow(value.slice(7));
    ui.camera.value = value;
    render();
  } else {
    if (following !== null && !value) follow(null);
    useCamera(value || null);
  }
});
window.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLInputElement && e.target.type !== 'range') return;
  if (e.key === ' ') { e.preventDefault(); setPlaying(!playing); }
  if (e.key === 'ArrowRight') { setPlaying(false); show(current + 1); }
  if (e.key === 'ArrowLeft') { setPlaying(false); show(current - 1); }
});
window.addEventListener('resize', () => { resize(); render(); });

function useCamera(name) {
  if (name && !shown.has(name)) throw new Error(`no camera named ${name}; cameras: ${cameras.join(', ')}`);
  if (name && !shown.get(name).lens) throw new Error(`${name} is not a camera`);
  lookThrough = name || null;
  controls.enabled = lookThrough === null;
  ui.camera.value = lookThrough || (following ? 'follow:' + following : '');
  render();
  return lookThrough;
}

// --------------------------------------------------------------------------------- the test API
function entryOf(name) {
  const entry = shown.get(name);
  if (!entry) throw new Error(`no object named ${name}`);
  return entry;
}
window.inbetween = {
  ready: false,
  fps: data.fps,
  frames: data.frames,
  objects: data.objects.map((o) => o.name),
  cameras,
  /** Shows the baked frame nearest to `frame` (paused) and returns the frame shown. */
  setFrame(frame) {
    setPlaying(false);
    let best = 0;
    for (let i = 1; i < frameCount; ++i) if (Math.abs(data.frames[i] - frame) < Math.abs(data.frames[best] - frame)) best = i;
    return show(best);
  },
  /** The frame shown. */
  frame: () => data.frames[current],
  /** The world position of the object as displayed (its three.js group), [x, y, z]. */
  objectPosition: (name) => entryOf(name).group.position.toArray(),
  /** The number of bones drawn (objects with a parent). */
  boneCount: () => boneChildren.length,
  /** Bone k as drawn: {parent, child, from: [x, y, z], to: [x, y, z]} (the line's two vertices). */
  bone: (k) => {
    const a = bones.geometry.getAttribute('position');
    const i = boneChildren[k];
    return { parent: data.objects[data.objects[i].parent].name, child: data.objects[i].name,
             from: [a.getX(2 * k), a.getY(2 * k), a.getZ(2 * k)], to: [a.getX(2 * k + 1), a.getY(2 * k + 1), a.getZ(2 * k + 1)] };
  },
  /** Names of the objects that draw a trajectory (trail) line. */
  trails: () => [...shown.values()].filter((e) => e.trajectory).map((e) => e.object.name),
  /** The world rotation of the object as displayed, [w, x, y, z]. */
  objectRotation: (name) => { const q = entryOf(name).group.quaternion; return [q.w, q.x, q.y, q.z]; },
  /** Looks through the scene camera `name` (null: the free orbit camera); returns the name. */
  useCamera,
  /** Makes the free view follow the root `name` (null: stop, and frame the whole scene); returns the name. */
  follow: (name) => { const f = follow(name); ui.camera.value = f ? 'follow:' + f : ''; render(); return f; },
  /** The root the free view follows, or null. */
  following: () => following,
  /** The camera looked through, or null. */
  camera: () => lookThrough,
  play: () => setPlaying(true),
  pause: () => setPlaying(false),
};

resize();
if (many && followable.length > 0) {
  // A character: follow the root with the most descendants (frame 0's pose sets the distance).
  applyFrame(0);
  const root = followable.reduce((a, b) => (descendants[b] > descendants[a] ? b : a));
  follow(data.objects[root].name);
  ui.camera.value = 'follow:' + following;
}
show(0);
window.inbetween.ready = true;
document.body.dataset.ready = 'true';
