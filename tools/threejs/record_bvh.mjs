// Records three.js's world transforms of a BVH clip for tests/io/bvh_reference_test.cpp
// (tests/data/bvh/README.md says how to regenerate and what the file holds).
// usage:  node tools/threejs/record_bvh.mjs CLIP.bvh OUT.threejs.bin
// OUT: one line of JSON (the header), then little-endian float32 values, frame-major: for each frame
// and joint (file order) the world translation x y z and rotation w x y z (Matrix4.decompose of the
// bone's matrixWorld after AnimationMixer plays the frame; tools/threejs/bvh_world.mjs).
import { createHash } from 'node:crypto';
import { readFileSync, writeFileSync, renameSync } from 'node:fs';
import { basename } from 'node:path';
import { bakeWorld, positionedJointsWithOffset, threeVersion } from './bvh_world.mjs';

const [clipPath, outPath] = process.argv.slice(2);
if (!clipPath || !outPath) {
  console.error('usage: node record_bvh.mjs CLIP.bvh OUT.threejs.bin');
  process.exit(2);
}
const bytes = readFileSync(clipPath);
const text = bytes.toString('latin1');

// three.js adds position channels to the OFFSET; Blender and inbetween replace it.  The recording is
// a reference for inbetween only where the two readings coincide: refuse a clip where they differ.
const differing = positionedJointsWithOffset(text);
if (differing.length > 0) {
  console.error(`record_bvh: ${clipPath}: joints with position channels and a non-zero OFFSET ` +
                `(three.js adds, Blender and inbetween replace): ${differing.map((d) => d.name).join(', ')}`);
  process.exit(1);
}

const declared = Number(/Frames:\s*(\d+)/.exec(text)[1]);
const frameTime = Number(/Frame Time:\s*([-+0-9.eE]+)/.exec(text)[1]);
let values = null;
let worstScaleError = 0;
const bvh = bakeWorld(text, (i, row) => {
  const joints = row.length / 10;
  if (values === null) values = new Float32Array(declared * joints * 7);
  for (let j = 0; j < joints; ++j) {
    for (let k = 0; k < 7; ++k) values[(i * joints + j) * 7 + k] = row[j * 10 + k];
    for (let k = 7; k < 10; ++k) worstScaleError = Math.max(worstScaleError, Math.abs(row[j * 10 + k] - 1));
  }
});
const frames = bvh.times.length;
const header = {
  format: 'inbetween-bvh-reference-1',
  tool: `three.js ${threeVersion} BVHLoader + AnimationMixer (Node ${process.version})`,
  source: basename(clipPath),
  source_bytes: bytes.length,
  source_sha256: createHash('sha256').update(bytes).digest('hex'),
  declared_frames: declared,
  frames,
  frame_time: frameTime,
  joints: bvh.names,
  values: ['tx', 'ty', 'tz', 'qw', 'qx', 'qy', 'qz'],
  dtype: 'float32 little-endian',
  layout: 'frame, joint, value',
  sampled_at: 'the key time of MOTION line i, float32(i * Frame Time) as three.js stores it',
  world_scale_max_deviation_from_1: worstScaleError,
};
const data = Buffer.from(values.buffer, values.byteOffset, frames * bvh.names.length * 7 * 4);
const tmp = `${outPath}.tmp`;
writeFileSync(tmp, Buffer.concat([Buffer.from(JSON.stringify(header) + '\n', 'utf8'), data]));
renameSync(tmp, outPath);
console.log(`record_bvh: ${outPath}: ${frames} frames × ${bvh.names.length} joints (three.js ${threeVersion}), ` +
            `world scale within ${worstScaleError.toExponential(1)} of 1`);
