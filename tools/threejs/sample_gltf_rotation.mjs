// Independent reference: samples a glTF CUBICSPLINE rotation channel with three.js's own GLTFLoader
// and AnimationMixer, headless in Node.
// stdin:  {"times": [t...], "keys": [[w,x,y,z]...], "in_tangents": [[w,x,y,z]...],
//          "out_tangents": [[w,x,y,z]...], "samples": [t...]}
// stdout: [[w,x,y,z] per sample]
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { readFileSync } from 'node:fs';

// three's FileLoader reports progress with the browser's ProgressEvent, which Node lacks.
globalThis.ProgressEvent ??= class extends Event {
  constructor(type, init = {}) { super(type); Object.assign(this, init); }
};

const req = JSON.parse(readFileSync(0, 'utf8'));
const xyzw = (q) => [q[1], q[2], q[3], q[0]];  // glTF stores quaternions x, y, z, w
const output = [];
req.keys.forEach((q, k) => output.push(...xyzw(req.in_tangents[k]), ...xyzw(q), ...xyzw(req.out_tangents[k])));
const data = new Float32Array([...req.times, ...output]);
const gltf = {
  asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ name: 'node' }],
  buffers: [{ byteLength: data.byteLength,
              uri: 'data:application/octet-stream;base64,' + Buffer.from(data.buffer).toString('base64') }],
  bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: 4 * req.times.length },
                { buffer: 0, byteOffset: 4 * req.times.length, byteLength: 4 * output.length }],
  accessors: [{ bufferView: 0, componentType: 5126, count: req.times.length, type: 'SCALAR',
                min: [Math.min(...req.times)], max: [Math.max(...req.times)] },
              { bufferView: 1, componentType: 5126, count: output.length / 4, type: 'VEC4' }],
  animations: [{ channels: [{ sampler: 0, target: { node: 0, path: 'rotation' } }],
                 samplers: [{ input: 0, output: 1, interpolation: 'CUBICSPLINE' }] }],
};
new GLTFLoader().parse(JSON.stringify(gltf), '', (result) => {
  const mixer = new THREE.AnimationMixer(result.scene);
  mixer.clipAction(result.animations[0]).play();
  const node = result.scene.getObjectByName('node');
  const out = req.samples.map((t) => {
    mixer.setTime(t);
    const q = node.quaternion;
    return [q.w, q.x, q.y, q.z];
  });
  process.stdout.write(JSON.stringify(out) + '\n');
}, (error) => { console.error(String(error)); process.exit(1); });
