// Validates every glTF file named on the command line with the Khronos glTF-Validator and
// prints one JSON line per file: {"file", "errors", "codes"} (the error codes, deduplicated).
// A file the validator cannot read at all counts as one error, "UNREADABLE"; one it fails on
// (an exception it does not catch, e.g. on a number beyond double range) as "VALIDATOR_FAILED".
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";

const validator = createRequire(import.meta.url)("gltf-validator");

// The validator's own failures surface as uncaught exceptions: they end the file at hand.
let failCurrent = () => {};
process.on("unhandledRejection", () => failCurrent());
process.on("uncaughtException", () => failCurrent());

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const failed = new Promise((resolve) => {
    failCurrent = () => resolve({ file, errors: 1, codes: ["VALIDATOR_FAILED"] });
    setTimeout(failCurrent, 20000).unref();
  });
  return Promise.race([failed, report(file, bytes)]);
}

async function report(file, bytes) {
  try {
    const report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      maxIssues: 0,
      externalResourceFunction: (uri) =>
        new Promise((resolve, reject) =>
          fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) => (err ? reject(err.toString()) : resolve(data)))),
    });
    const codes = [...new Set(report.issues.messages.filter((m) => m.severity === 0).map((m) => m.code))];
    return { file, errors: report.issues.numErrors, codes };
  } catch (e) {
    return { file, errors: 1, codes: ["UNREADABLE"] };
  }
}

for (const file of process.argv.slice(2)) console.log(JSON.stringify(await validate(file)));
