// Independent reference: plays a whole glTF file's first animation with three.js's GLTFLoader and
// AnimationMixer, headless in Node, and prints every named node's world transform at given times.
// usage: node sample_gltf_scene.mjs FILE < {"times": [t...]}
// stdout: {"nodes": {"<node name>": [[tx,ty,tz, qw,qx,qy,qz, sx,sy,sz] per time], ...},
//          "cameras": {"<node name>": {"type", "fov_deg", "aspect", "near", "far",
//                                      "view": [[dx,dy,dz] per time]}, ...}}
// where a camera's view is three.js's Camera.getWorldDirection (the world direction it looks in,
// its −Z axis) and fov its vertical field of view in degrees.
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
  const out = { nodes: {}, cameras: {} };
  for (const n of nodes) {
    out.nodes[n.name] = [];
    if (n.isCamera) {
      out.cameras[n.name] = { type: n.type, fov_deg: n.fov, aspect: n.aspect, near: n.near, far: n.far, view: [] };
    }
  }
  const p = new THREE.Vector3(), q = new THREE.Quaternion(), s = new THREE.Vector3(), d = new THREE.Vector3();
  for (const t of req.times) {
    mixer.setTime(t);
    result.scene.updateMatrixWorld(true);
    for (const n of nodes) {
      n.matrixWorld.decompose(p, q, s);
      out.nodes[n.name].push([p.x, p.y, p.z, q.w, q.x, q.y, q.z, s.x, s.y, s.z]);
      if (n.isCamera) {
        n.getWorldDirection(d);
        out.cameras[n.name].view.push([d.x, d.y, d.z]);
      }
    }
  }
  process.stdout.write(JSON.stringify(out) + '\n');
}, (error) => { console.error(String(error)); process.exit(1); });
