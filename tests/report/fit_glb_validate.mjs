// Validates a .glb with the Khronos glTF validator (npm gltf-validator, installed in
// report/node_modules). Usage: node fit_glb_validate.mjs FILE.glb
// Prints the report's issue summary and messages as JSON; exits 1 when the file has
// validation errors, 2 when the validator cannot run.
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const reportDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../report');
const require = createRequire(path.join(reportDir, 'package.json'));

const file = process.argv[2];
if (!file) {
  console.error('usage: node fit_glb_validate.mjs FILE.glb');
  process.exit(2);
}
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error(`gltf-validator is not installed in ${reportDir}/node_modules (run scripts/install-deps.sh): ${e.message}`);
  process.exit(2);
}
const bytes = new Uint8Array(fs.readFileSync(file));
const result = await validator.validateBytes(bytes, { uri: path.basename(file), maxIssues: 100 });
const issues = result.issues;
console.log(JSON.stringify({
  validatorVersion: result.validatorVersion,
  numErrors: issues.numErrors,
  numWarnings: issues.numWarnings,
  numInfos: issues.numInfos,
  numHints: issues.numHints,
  messages: issues.messages.map((m) => `${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code} ${m.pointer ?? ''}: ${m.message}`),
  info: result.info,
}, null, 2));
process.exit(issues.numErrors === 0 ? 0 : 1);
