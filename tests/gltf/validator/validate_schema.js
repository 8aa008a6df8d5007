// Validates a JSON instance against a JSON Schema (draft 2020-12) with ajv and prints
// one JSON line: {"valid":true|false,"errors":[...]}. Exit 0 when valid, 1 when not,
// 2 on usage or I/O errors.
// Usage: node validate_schema.js SCHEMA.json INSTANCE.json
'use strict';
const fs = require('fs');
const Ajv2020 = require('ajv/dist/2020');

try {
  const [schemaFile, instanceFile] = process.argv.slice(2);
  if (!schemaFile || !instanceFile) throw new Error('usage: node validate_schema.js SCHEMA INSTANCE');
  const schema = JSON.parse(fs.readFileSync(schemaFile, 'utf8'));
  const instance = JSON.parse(fs.readFileSync(instanceFile, 'utf8'));
  // strict: unknown keywords in the schema are errors, so the schema itself is checked too.
  const ajv = new Ajv2020({ strict: true, allErrors: true });
  // The glTF schema vocabulary: annotation keywords and the two base schemas every
  // Khronos extension schema refers to (same definitions as glTF 2.0's own files).
  for (const keyword of ['gltf_detailedDescription', 'gltf_webgl', 'gltf_uriType', 'gltf_sectionDescription']) {
    ajv.addKeyword({ keyword, schemaType: 'string' });
  }
  ajv.addSchema({
    $id: 'glTFid.schema.json', type: 'integer', minimum: 0,
  });
  ajv.addSchema({
    $id: 'glTFProperty.schema.json', type: 'object',
    properties: {
      extensions: { type: 'object', additionalProperties: { type: 'object' } },
      extras: {},
    },
  });
  const validate = ajv.compile(schema);
  const valid = validate(instance);
  process.stdout.write(JSON.stringify({ valid, errors: validate.errors || [] }) + '\n');
  process.exit(valid ? 0 : 1);
} catch (e) {
  process.stderr.write(`validate_schema.js: ${e && e.message ? e.message : e}\n`);
  process.exit(2);
}
