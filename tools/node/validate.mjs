// Runs the Khronos glTF-Validator (npm gltf-validator) over .gltf and .glb files and
// prints, for each, "FILE: N errors, N warnings, N infos, N hints" and then its errors and
// warnings, one per line: "error CODE POINTER: message".
// Exit code: 0 when no file has errors, 1 when one has, 2 when a file or the validator
// cannot be read. Usage: node tools/node/validate.mjs FILE...
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";

const require = createRequire(import.meta.url);
const files = process.argv.slice(2);
if (files.length === 0) {
  console.error("usage: node validate.mjs FILE.gltf|FILE.glb...");
  process.exit(2);
}
let validator;
try {
  validator = require("gltf-validator");
} catch (e) {
  console.error("validate.mjs: gltf-validator is not installed (scripts/install-deps.sh installs it): " + e.message);
  process.exit(2);
}
async function validate(file) {
  let bytes;
  try {
    bytes = new Uint8Array(fs.readFileSync(file));
  } catch (e) {
    console.error("validate.mjs: " + file + ": " + e.message);
    return 2;
  }
  const dir = path.dirname(path.resolve(file));
  let report;
  try {
    report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      maxIssues: 0,
      externalResourceFunction: (uri) =>
        new Promise((resolve, reject) => {
          fs.readFile(path.resolve(dir, decodeURIComponent(uri)), (err, data) =>
            err ? reject(err.toString()) : resolve(new Uint8Array(data)));
        }),
    });
  } catch (e) {  // not even glTF: the validator's own verdict, an error
    console.log(`${file}: 1 errors (the validator refused it: ${String(e).split("\n")[0]})`);
    return 1;
  }
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
  const severity = ["error", "warning", "info", "hint"];
  for (const m of i.messages)
    if (m.severity <= 1) console.log(`${severity[m.severity]} ${m.code} ${m.pointer ?? ""}: ${m.message}`);
  return i.numErrors > 0 ? 1 : 0;
}

let worst = 0;
for (const f of files) worst = Math.max(worst, await validate(f));
process.exit(worst);
