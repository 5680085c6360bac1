// The Khronos glTF-Validator (npm gltf-validator, pinned in package.json) over the glTF corpus Obscura is tested on,
// beside what Obscura's loader does with each file (obscura-gltf-check): Debian's assimp-testmodels, the project's
// assets (the files its tools make: obscura-make-room, obscura-make-pbr-samples, obscura-make-glass-samples).
//
//   node conformance.mjs --loader BUILD/obscura-gltf-check [--markdown FILE] [--quiet]
//
// Fails (exit status 1) where
//   - a file the validator calls valid (no error) does not load, unless its refusal names an extension it requires
//     that docs/robustness.md lists as unsupported ("requires ... extension");
//   - a file the validator calls invalid loads without a word: it must be refused in one line, or load with at least
//     one warning naming what was repaired or ignored;
//   - a refusal is not one line.
// --markdown writes the table docs/robustness.md holds ("glTF-Validator against the loader").
import { execFileSync } from 'node:child_process';
import { readFileSync, readdirSync, statSync, writeFileSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import validator from 'gltf-validator';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '..', '..');
const args = process.argv.slice(2);
const option = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
const loader = option('--loader');
const markdown = option('--markdown');
const quiet = args.includes('--quiet');
if (!loader) {
  console.error('usage: node conformance.mjs --loader PATH/obscura-gltf-check [--markdown FILE] [--quiet]');
  process.exit(2);
}

function gltfFiles(dir) {
  let out = [];
  let entries = [];
  try {
    entries = readdirSync(dir);
  } catch {
    return out;
  }
  for (const name of entries.sort()) {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) out = out.concat(gltfFiles(path));
    else if (/\.(gltf|glb)$/i.test(name)) out.push(path);
  }
  return out;
}

const corpus = [
  ...gltfFiles('/usr/share/assimp/models/glTF2'),
  ...gltfFiles(join(root, 'assets')),
];
if (corpus.length === 0) {
  console.error('no glTF files found (is assimp-testmodels installed?)');
  process.exit(1);
}

// The loader, many files per process.
const loaded = new Map();
for (let i = 0; i < corpus.length; i += 50) {
  const out = execFileSync(loader, corpus.slice(i, i + 50), { encoding: 'utf8', maxBuffer: 1 << 26 });
  for (const line of out.split('\n').filter((l) => l.trim())) {
    const result = JSON.parse(line);
    loaded.set(result.file, result);
  }
}

async function validate(path) {
  const bytes = new Uint8Array(readFileSync(path));
  try {
    return await validator.validateBytes(bytes, {
      uri: path,
      maxIssues: 0,
      externalResourceFunction: (uri) =>
        new Promise((ok, fail) => {
          try {
            ok(new Uint8Array(readFileSync(join(dirname(path), decodeURIComponent(uri)))));
          } catch (e) {
            fail(e.toString());
          }
        }),
    });
  } catch (e) {
    return { issues: { numErrors: 1, numWarnings: 0, messages: [{ code: 'UNREADABLE', message: String(e) }] } };
  }
}

const rows = [];
const failures = [];
for (const path of corpus) {
  const report = await validate(path);
  const issues = report.issues;
  const codes = [...new Set(issues.messages.filter((m) => m.severity === 0 || m.severity === undefined)
    .map((m) => m.code))];
  const result = loaded.get(path);
  const name = path.startsWith('/usr/share/assimp/models/glTF2/')
    ? relative('/usr/share/assimp/models/glTF2', path)
    : relative(root, path);
  const valid = issues.numErrors === 0;
  const row = {
    name,
    valid,
    errors: issues.numErrors,
    warnings: issues.numWarnings,
    codes,
    loaded: result.loaded,
    refusal: result.refusal,
    obscuraWarnings: result.warnings,
  };
  rows.push(row);
  if (!result.loaded && result.refusal.includes('\n')) failures.push(`${name}: the refusal is not one line`);
  if (valid && !result.loaded && !/requires (unsupported extension|KHR_|EXT_)/.test(result.refusal))
    failures.push(`${name}: valid by the validator, refused: ${result.refusal}`);
  if (!valid && result.loaded && result.warnings.length === 0)
    failures.push(`${name}: invalid by the validator (${codes.join(', ')}), loaded without a warning`);
}

const valid = rows.filter((r) => r.valid).length;
const loadedCount = rows.filter((r) => r.loaded).length;
if (!quiet)
  console.log(`gltf-validator ${validator.version()}: ${rows.length} files, ${valid} valid; Obscura loads ` +
              `${loadedCount}, refuses ${rows.length - loadedCount}`);

if (markdown) {
  const cell = (text) => text.replace(/\|/g, '\\|').replace(/\n/g, ' ');
  const shorten = (text, n) => (text.length > n ? text.slice(0, n - 1) + '…' : text);
  let md = `| file | glTF-Validator ${validator.version()} | Obscura |\n|---|---|---|\n`;
  for (const r of rows) {
    const verdict = r.valid
      ? `valid${r.warnings ? ` (${r.warnings} warnings)` : ''}`
      : `**invalid**: ${r.errors} errors (${shorten(r.codes.join(', '), 80)})`;
    const obscura = r.loaded
      ? `loads${r.obscuraWarnings.length ? `; ${r.obscuraWarnings.length} warnings: ` +
          shorten(r.obscuraWarnings.slice(0, 2).join('; '), 120) : ''}`
      : `**refused**: ${shorten(r.refusal.replace(/^.*?: /, ''), 140)}`;
    md += `| ${cell(r.name)} | ${cell(verdict)} | ${cell(obscura)} |\n`;
  }
  writeFileSync(markdown, md);
}

for (const f of failures) console.error(`FAIL ${f}`);
process.exit(failures.length ? 1 : 0);
