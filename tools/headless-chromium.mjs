// How every headless Chromium of the project is launched (the browser tests, the browser benchmark and its
// scripts): Debian's /usr/bin/chromium (nothing is downloaded), WebGL through ANGLE on SwiftShader, nothing from the
// network. Playwright's chromium.launch(chromiumLaunchOptions) takes it; this module imports no package, so both npm
// folders (tests/browser, tools/browser-bench) can share it.
export const chromiumFlags = ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
                              '--disable-background-networking', '--disable-component-update', '--disable-sync',
                              '--no-first-run', '--disable-quic'];

export const chromiumLaunchOptions = { executablePath: '/usr/bin/chromium', headless: true, args: chromiumFlags };

// Command-line options of the form --name VALUE, for the small scripts: `handlers` maps each option to a function
// that takes its value. Throws on an unknown option or a missing value, naming `script` for its usage.
export function parseOptions(argv, handlers, script) {
  for (let i = 0; i < argv.length; ++i) {
    const handler = handlers[argv[i]];
    if (!handler) throw new Error(`unknown option ${argv[i]} (see the header of ${script})`);
    if (i + 1 >= argv.length) throw new Error(`${argv[i]} needs a value`);
    handler(argv[++i]);
  }
}
