// Validates glTF files with Khronos' glTF-Validator (npm gltf-validator), for scripts/make-test-assets.sh:
// prints each file's counts of errors, warnings and infos; exits 1 when any file has an error.
//   node scripts/gltf/validate.js FILE.gltf|FILE.glb...   (with gltf-validator in NODE_PATH)
const validator = require('gltf-validator');
const fs = require('fs');
const path = require('path');
(async () => {
  let failed = false;
  for (const file of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      externalResourceFunction: (uri) => Promise.resolve(new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(uri))))),
    });
    const i = report.issues;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos (${report.validatorVersion})`);
    if (i.numErrors > 0) { failed = true; console.log(JSON.stringify(i.messages.slice(0, 5))); }
  }
  process.exit(failed ? 1 : 0);
})();
