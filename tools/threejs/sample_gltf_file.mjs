// Independent reference for glTF import: three.js's GLTFLoader loads a .glb or .gltf (embedded
// buffers) and AnimationMixer plays one animation, headless in Node; every node's world transform
// (matrixWorld decomposed) and morph weights are printed at the requested times.
// usage:  node sample_gltf_file.mjs MODEL < {"animation": INDEX, "times": [t...]}
// stdout: {"nodes": {"<node index>": [[tx,ty,tz, qw,qx,qy,qz, sx,sy,sz] per time]},
//          "weights": {"<node index>": [[w0, w1, ...] per time]}}
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { readFileSync } from 'node:fs';

// three's FileLoader reports progress with the browser's ProgressEvent, which Node lacks.
globalThis.ProgressEvent ??= class extends Event {
  constructor(type, init = {}) { super(type); Object.assign(this, init); }
};

const req = JSON.parse(readFileSync(0, 'utf8'));
const bytes = readFileSync(process.argv[2]);
const data = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);

new GLTFLoader().parse(data, '', (gltf) => {
  // Objects made for node i: the loader's association map (names are sanitised, indices are not).
  const byNode = new Map();
  gltf.scene.traverse((obj) => {
    const a = gltf.parser.associations.get(obj);
    if (a && a.nodes !== undefined && !byNode.has(a.nodes)) byNode.set(a.nodes, obj);
  });
  const mixer = new THREE.AnimationMixer(gltf.scene);
  const action = mixer.clipAction(gltf.animations[req.animation]);
  action.setLoop(THREE.LoopOnce, 1);
  action.clampWhenFinished = true;  // hold the last key at the end instead of stopping
  const out = { nodes: {}, weights: {} };
  for (const i of byNode.keys()) {
    out.nodes[i] = [];
    if (byNode.get(i).morphTargetInfluences) out.weights[i] = [];
  }
  const p = new THREE.Vector3(), q = new THREE.Quaternion(), s = new THREE.Vector3();
  for (const t of req.times) {
    action.reset();  // un-pause after a finished pass; time 0
    action.play();
    mixer.setTime(t);
    gltf.scene.updateMatrixWorld(true);
    for (const [i, obj] of byNode) {
      obj.matrixWorld.decompose(p, q, s);
      out.nodes[i].push([p.x, p.y, p.z, q.w, q.x, q.y, q.z, s.x, s.y, s.z]);
      if (obj.morphTargetInfluences) out.weights[i].push([...obj.morphTargetInfluences]);
    }
  }
  process.stdout.write(JSON.stringify(out) + '\n');
}, (error) => { console.error(String(error)); process.exit(1); });
