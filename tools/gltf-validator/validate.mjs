// Runs the Khronos glTF validator on one .gltf or .glb file.
// usage: node validate.mjs FILE  →  prints the validator's JSON report; exit 0 when it has no error.
import validator from 'gltf-validator';
import { readFileSync } from 'node:fs';
import path from 'node:path';

const file = process.argv[2];
const bytes = new Uint8Array(readFileSync(file));
const report = await validator.validateBytes(bytes, {
  uri: path.basename(file),
  externalResourceFunction: (uri) => Promise.resolve(new Uint8Array(readFileSync(path.join(path.dirname(file), decodeURIComponent(uri))))),
});
process.stdout.write(JSON.stringify(report, null, 1) + '\n');
process.exit(report.issues.numErrors === 0 ? 0 : 1);
