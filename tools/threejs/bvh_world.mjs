// three.js as an independent reference for BVH: BVHLoader parses the file, an AnimationMixer plays
// its clip on the loader's Bone hierarchy, and every joint's world transform (matrixWorld
// decomposed) is read at every frame.  Shared by tools/threejs/record_bvh.mjs (the recorded test
// data in tests/data/bvh/) and tools/bench/bvh_threejs.mjs (the speed comparison), so both do the
// same work.
//
// What three.js does that matters for a comparison (three 0.187.0, examples/jsm/loaders/BVHLoader.js):
// - Frame i is the i-th MOTION line for i < the declared `Frames:` count; extra lines are ignored.
// - Position channels are ADDED to the joint's OFFSET (Blender 3.4 and inbetween REPLACE it): the
//   two agree only where a joint with position channels has a zero OFFSET.  jointsWithPositions()
//   lists those joints so a recorder can say whether that holds.
// - Key times and values are stored in Float32Arrays (KeyframeTrack's buffer types): key values are
//   float-rounded (quaternions computed in double, then stored as float), and the key time of frame
//   i is float32(i · Frame Time).  Sampling at that stored time lands exactly on the key (the
//   interpolants return the key itself at weight 0), so no neighbouring frame leaks in.
// - End Sites become Bones named 'ENDSITE' with no tracks; they are not joints here.
import * as THREE from 'three';
import { BVHLoader } from 'three/examples/jsm/loaders/BVHLoader.js';

/** The installed three.js version ('0.187.0'), from THREE.REVISION. */
export const threeVersion = `0.${THREE.REVISION}.0`;

/**
 * Parses BVH text with BVHLoader and prepares playback.
 * @returns {{names: string[], bones: THREE.Bone[], root: THREE.Bone, times: Float32Array,
 *            mixer: THREE.AnimationMixer, action: THREE.AnimationAction}}
 */
export function loadBvh(text) {
  const { skeleton, clip } = new BVHLoader().parse(text);
  const root = skeleton.bones[0];
  // Joints in file order: the bones that have a rotation track (every joint has one; End Sites none).
  const names = clip.tracks.filter((t) => t.name.endsWith('.quaternion')).map((t) => t.name.slice(0, -'.quaternion'.length));
  const bones = names.map((n) => skeleton.getBoneByName(n));
  const mixer = new THREE.AnimationMixer(root);
  const action = mixer.clipAction(clip);
  action.play();
  return { names, bones, root, times: clip.tracks[0].times, mixer, action };
}

/**
 * Poses the skeleton at frame `i` (the stored key time of MOTION line i) and updates world matrices.
 * action.time + mixer.update(0): a zero step neither loops nor clamps, so the last frame is the last key.
 */
export function poseFrame(bvh, i) {
  bvh.action.time = bvh.times[i];
  bvh.mixer.update(0);
  bvh.root.updateMatrixWorld(true);
}

/**
 * Loads `text` and bakes every frame: for each joint its world translation x y z, rotation w x y z
 * and scale x y z (Matrix4.decompose of matrixWorld) into `row` (joints × 10), then calls
 * onFrame(i, row).  Returns the loaded clip.
 */
export function bakeWorld(text, onFrame) {
  const bvh = loadBvh(text);
  const row = new Float64Array(bvh.names.length * 10);
  const p = new THREE.Vector3(), q = new THREE.Quaternion(), s = new THREE.Vector3();
  for (let i = 0; i < bvh.times.length; ++i) {
    poseFrame(bvh, i);
    for (let j = 0; j < bvh.bones.length; ++j) {
      bvh.bones[j].matrixWorld.decompose(p, q, s);
      const o = j * 10;
      row[o] = p.x; row[o + 1] = p.y; row[o + 2] = p.z;
      row[o + 3] = q.w; row[o + 4] = q.x; row[o + 5] = q.y; row[o + 6] = q.z;
      row[o + 7] = s.x; row[o + 8] = s.y; row[o + 9] = s.z;
    }
    if (onFrame) onFrame(i, row);
  }
  return bvh;
}

/** The BVH joints that have position channels and a non-zero OFFSET: where three.js's "add" and
 * Blender's "replace" differ.  [{name, offset: [x, y, z]}]. */
export function positionedJointsWithOffset(text) {
  const out = [];
  const lines = text.split(/\r?\n/);
  for (let k = 0; k < lines.length; ++k) {
    const head = lines[k].trim().split(/\s+/);
    if (head[0] !== 'ROOT' && head[0] !== 'JOINT') continue;
    const offset = lines[k + 2].trim().split(/\s+/).slice(1, 4).map(Number);
    const channels = lines[k + 3].trim().split(/\s+/);
    if (channels.some((c) => /position$/i.test(c)) && offset.some((v) => v !== 0)) out.push({ name: head.slice(1).join(' '), offset });
  }
  return out;
}
