// Runs the Khronos glTF validator on one .glb/.gltf file and prints one JSON line:
// {"errors":E,"warnings":W,"infos":I,"hints":H,"messages":[...]}.
// gltf-validator is a library without a command line, hence this wrapper.
// Usage: node validate_gltf.js FILE   (exit 0 when the report was produced)
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function main() {
  const file = process.argv[2];
  if (!file) throw new Error('usage: node validate_gltf.js FILE');
  const bytes = new Uint8Array(fs.readFileSync(file));
  const dir = path.dirname(file);
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    // External buffers and images of a .gltf are resolved beside it.
    externalResourceFunction: (uri) =>
      Promise.resolve(new Uint8Array(fs.readFileSync(path.join(dir, decodeURIComponent(uri))))),
  });
  const issues = report.issues;
  const messages = issues.messages.map((m) => `${m.severity}:${m.code}:${m.pointer || ''}:${m.message}`);
  process.stdout.write(JSON.stringify({
    errors: issues.numErrors,
    warnings: issues.numWarnings,
    infos: issues.numInfos,
    hints: issues.numHints,
    messages,
  }) + '\n');
}

main().catch((e) => {
  process.stderr.write(`validate_gltf.js: ${e && e.message ? e.message : e}\n`);
  process.exit(2);
});
