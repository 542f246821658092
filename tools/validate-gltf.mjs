#!/usr/bin/env node
// Runs the Khronos glTF validator on each file named on the command line. External resources (.bin,
// images) are read relative to the file, as a viewer would. Prints one line per file
// ("OK|FAIL file: E errors, W warnings") followed by every error and warning message, and exits 1 when
// any file has an error (warnings are listed but do not fail), 2 on a usage or read problem.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: validate-gltf.mjs FILE.glb|FILE.gltf ...');
  process.exit(2);
}

let failed = false;
for (const file of files) {
  let data;
  try {
    data = new Uint8Array(await readFile(file));
  } catch (e) {
    console.error(`${file}: cannot be read: ${e.message}`);
    process.exit(2);
  }
  const report = await validator.validateBytes(data, {
    uri: path.basename(file),
    maxIssues: 200,
    externalResourceFunction: (uri) =>
      readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const { numErrors, numWarnings, messages } = report.issues;
  failed ||= numErrors > 0;
  console.log(`${numErrors > 0 ? 'FAIL' : 'OK'} ${file}: ${numErrors} errors, ${numWarnings} warnings`);
  for (const m of messages) {
    if (m.severity > 1) continue;  // 0 error, 1 warning; infos and hints are noise here
    console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  }
}
process.exit(failed ? 1 : 0);
