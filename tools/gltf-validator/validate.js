// Validates one .glb/.gltf with the Khronos glTF validator and prints a JSON
// summary {errors, warnings, infos, hints, messages} on stdout.
// Exit code: 0 no errors, 1 errors, 2 the validator could not run.
'use strict';
const fs = require('fs');
const path = require('path');
let validator;
try {
  validator = require(path.join(__dirname, 'node_modules', 'gltf-validator'));
} catch (e) {
  console.error('gltf-validator is not installed: npm install --prefix ' + __dirname);
  process.exit(2);
}
const file = process.argv[2];
if (!file) {
  console.error('usage: node validate.js FILE.glb|FILE.gltf');
  process.exit(2);
}
const dir = path.dirname(path.resolve(file));
validator
    .validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      maxIssues: 0,
      writeTimestamp: false,
      externalResourceFunction: (uri) => new Promise((resolve, reject) => {
        fs.readFile(path.resolve(dir, decodeURIComponent(uri)),
                    (err, data) => err ? reject(err.toString()) : resolve(data));
      }),
    })
    .then((report) => {
      const i = report.issues;
      const summary = {
        validator: report.validatorVersion,
        errors: i.numErrors,
        warnings: i.numWarnings,
        infos: i.numInfos,
        hints: i.numHints,
        messages: i.messages.map((m) => `${m.severity} ${m.code} ${m.pointer || ''}: ${m.message}`),
      };
      console.log(JSON.stringify(summary, null, 1));
      process.exit(i.numErrors > 0 ? 1 : 0);
    }, (error) => {
      console.error('validator failed: ' + error);
      process.exit(2);
    });
