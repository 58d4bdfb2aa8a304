// The Khronos glTF validator (npm gltf-validator, installed by
// tools/install.sh under tools/node) on each .glb named: prints its report
// and a "counts" line per file; exits 1 on any error or warning, 2 when the
// validator is not installed.
import fs from 'fs';
import { createRequire } from 'module';

let validator;
for (const base of [new URL('../../tools/node/', import.meta.url), import.meta.url]) {
  try {
    validator = createRequire(base)('gltf-validator');
    break;
  } catch (e) { /* the next place */ }
}
if (!validator) {
  console.log('FAIL missing reader: gltf-validator (npm; install it with tools/install.sh)');
  process.exit(2);
}
let bad = 0;
for (const file of process.argv.slice(2)) {
  const r = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), { maxIssues: 50 });
  const i = r.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
  for (const m of i.messages) console.log(`  ${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  console.log(`counts ${file} vertices=${r.info.totalVertexCount} triangles=${r.info.totalTriangleCount} ` +
              `materials=${r.info.materialCount} generator=${JSON.stringify(r.info.generator)}`);
  if (i.numErrors > 0 || i.numWarnings > 0) bad = 1;
}
process.exit(bad);
