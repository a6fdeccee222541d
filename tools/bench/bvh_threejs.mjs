// The peer of bench/io_bench.cpp's BM_BvhReadBakeWorld (issue 20, "Speed"): three.js reads a BVH
// file with BVHLoader and bakes it in world space — every frame played by an AnimationMixer, every
// joint's matrixWorld decomposed into translation, rotation and scale (10 numbers) written into
// one preallocated row (tools/threejs/bvh_world.mjs, the same code that records the test
// references).  One untimed warm-up run lets V8 compile the hot code (a generous reading for
// three.js: a tool loading one clip runs cold; the cold first run is reported too), then
// --repetitions timed runs; the medians of process CPU time (process.cpuUsage: user + system,
// V8's helper threads included, since they do the work) and of wall time are printed and, with
// --json, written in Google Benchmark's JSON layout for tools/bench/write_results.py.
//
// usage: node tools/bench/bvh_threejs.mjs CLIP.bvh [--repetitions N] [--json OUT.json]
// Without three.js (`npm ci --prefix tools/threejs`) it prints one "not run: …" line, writes
// {"not_run": reason} to OUT.json and exits 0.
import { readFileSync, writeFileSync } from 'node:fs';
import { basename } from 'node:path';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : fallback;
};
const clip = args.find((a, i) => !a.startsWith('--') && (i === 0 || !args[i - 1].startsWith('--')));
const repetitions = Number(option('--repetitions', '5'));
const jsonOut = option('--json', null);
if (!clip || !(repetitions >= 1)) {
  console.error('usage: node bvh_threejs.mjs CLIP.bvh [--repetitions N] [--json OUT.json]');
  process.exit(2);
}

function notRun(reason) {
  console.log(`not run: ${reason}`);
  if (jsonOut) writeFileSync(jsonOut, JSON.stringify({ not_run: reason }) + '\n');
  process.exit(0);
}

let world;
try {
  world = await import('../threejs/bvh_world.mjs');
} catch (e) {
  notRun(`three.js is not installed (npm ci --prefix tools/threejs): ${String(e.message).split('\n')[0]}`);
}
let probe;
try {
  probe = readFileSync(clip);
} catch (e) {
  notRun(`${clip} cannot be read (Debian assimp-testmodels): ${e.code ?? e.message}`);
}

let sink = 0;  // keeps the baked values alive, as benchmark::DoNotOptimize does on the C++ side
let shape = null;
function once() {
  const cpu0 = process.cpuUsage();
  const t0 = performance.now();
  const text = readFileSync(clip, 'latin1');
  const bvh = world.bakeWorld(text, (i, row) => { sink += row[0] + row[row.length - 1]; });
  const wall = performance.now() - t0;
  const cpu = process.cpuUsage(cpu0);
  shape = { frames: bvh.times.length, joints: bvh.names.length };
  return { cpu_ms: (cpu.user + cpu.system) / 1000, wall_ms: wall };
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
};

const cold = once();
const runs = [];
for (let r = 0; r < repetitions; ++r) runs.push(once());
const cpu = median(runs.map((x) => x.cpu_ms));
const wall = median(runs.map((x) => x.wall_ms));
const name = `BM_BvhThreeJs/${basename(clip, '.bvh')}`;
console.log(`${name}: median of ${repetitions} after one warm-up: ${cpu.toFixed(1)} ms CPU, ${wall.toFixed(1)} ms wall ` +
            `(cold first run ${cold.cpu_ms.toFixed(1)} ms CPU, ${cold.wall_ms.toFixed(1)} ms wall); ` +
            `${shape.frames} frames x ${shape.joints} joints, three.js ${world.threeVersion}, Node ${process.version}` +
            (Number.isFinite(sink) ? '' : ' (non-finite output!)'));
if (jsonOut) {
  const doc = {
    context: {
      date: new Date().toISOString(), node: process.version, three: world.threeVersion, clip,
      clip_bytes: probe.length, repetitions, warmup_runs: 1,
      cold_cpu_ms: cold.cpu_ms, cold_real_ms: cold.wall_ms,
      runs_cpu_ms: runs.map((x) => x.cpu_ms), runs_real_ms: runs.map((x) => x.wall_ms),
    },
    benchmarks: [{
      name: `${name}_median`, run_name: name, run_type: 'aggregate', aggregate_name: 'median',
      repetitions, cpu_time: cpu, real_time: wall, time_unit: 'ms', wall_ms: wall, frames: shape.frames, joints: shape.joints,
    }],
  };
  writeFileSync(jsonOut, JSON.stringify(doc, null, 1) + '\n');
}
