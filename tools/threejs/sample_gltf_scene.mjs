// Independent reference: plays a whole glTF file's first animation with three.js's GLTFLoader and
// AnimationMixer, headless in Node, and prints every named node's world transform at given times.
// usage: node sample_gltf_scene.mjs FILE < {"times": [t...]}
// stdout: {"<node name>": [[tx,ty,tz, qw,qx,qy,qz, sx,sy,sz] per time], ...}
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { readFileSync } from 'node:fs';

globalThis.ProgressEvent ??= class extends Event {
  constructor(type, init = {}) { super(type); Object.assign(this, init); }
};

const req = JSON.parse(readFileSync(0, 'utf8'));
const bytes = readFileSync(process.argv[2]);
const data = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
new GLTFLoader().parse(data, '', (result) => {
  const mixer = new THREE.AnimationMixer(result.scene);
  if (result.animations.length > 0) {
    // Play once and hold the last pose: a looping action wraps t = duration back to 0.
    const action = mixer.clipAction(result.animations[0]);
    action.setLoop(THREE.LoopOnce);
    action.clampWhenFinished = true;
    action.play();
  }
  const nodes = [];
  result.scene.traverse((o) => { if (o.name && o !== result.scene) nodes.push(o); });
  const out = {};
  for (const n of nodes) out[n.name] = [];
  const p = new THREE.Vector3(), q = new THREE.Quaternion(), s = new THREE.Vector3();
  for (const t of req.times) {
    mixer.setTime(t);
    result.scene.updateMatrixWorld(true);
    for (const n of nodes) {
      n.matrixWorld.decompose(p, q, s);
      out[n.name].push([p.x, p.y, p.z, q.w, q.x, q.y, q.z, s.x, s.y, s.z]);
    }
  }
  process.stdout.write(JSON.stringify(out) + '\n');
}, (error) => { console.error(String(error)); process.exit(1); });
