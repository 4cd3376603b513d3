// Validates glTF files with Khronos' glTF-Validator (npm gltf-validator): prints each file's
// error and warning counts and the first messages; exits 1 when any file has an error.
import { readFile } from 'node:fs/promises';
import validator from 'gltf-validator';

let failed = false;
for (const path of process.argv.slice(2)) {
  const report = await validator.validateBytes(new Uint8Array(await readFile(path)), {
    maxIssues: 100,
  });
  const { numErrors, numWarnings, messages } = report.issues;
  console.log(`${path}: ${numErrors} errors, ${numWarnings} warnings`);
  for (const m of messages.slice(0, 10))
    console.log(`  ${m.severity === 0 ? 'error' : 'note'} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  failed ||= numErrors > 0;
}
process.exit(failed ? 1 : 0);
