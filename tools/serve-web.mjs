#!/usr/bin/env node
// A static file server for the demo page (build-web/site), bound to 127.0.0.1 only. Used by tools/run.sh and by the
// browser tests (which import startServer). Usage: node tools/serve-web.mjs [root] [port]
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',  // needed for WebAssembly.instantiateStreaming
  '.png': 'image/png',
  '.json': 'application/json',
  '.glb': 'model/gltf-binary',
};

// Resolves to the listening server; port 0 picks a free one (server.address().port). server.stop() closes it
// together with the browser's idle keep-alive connections, which would otherwise hold the process open.
// `mounts` serve more than `root`: {'/prefix/': directory} serves a folder under a URL prefix, {'/exact/path': file}
// one file (the browser benchmark mounts its pages, node_modules and the model). `root` may be null: mounts only.
// `isolated`: the pages are cross-origin isolated (COOP and COEP headers), which gives performance.now() a resolution
// of microseconds where a page without isolation gets a tenth of a millisecond (the host-time scripts).
export function startServer(root, port = 0, mounts = {}, { isolated = false } = {}) {
  const base = root === null ? null : path.resolve(root);
  // The file a URL path names, or null: mounted first, then under root; never outside the folder it is served from.
  const resolve = (pathname) => {
    for (const [prefix, target] of Object.entries(mounts)) {
      if (pathname === prefix && !prefix.endsWith('/')) return target;
      if (prefix.endsWith('/') && pathname.startsWith(prefix)) {
        const folder = path.resolve(target);
        const file = path.join(folder, pathname.slice(prefix.length) || 'index.html');
        return file.startsWith(folder + path.sep) ? file : null;
      }
    }
    if (base === null) return null;
    const file = path.join(base, pathname === '/' ? '/index.html' : pathname);
    return file.startsWith(base + path.sep) ? file : null;
  };
  const server = http.createServer((request, response) => {
    const url = new URL(request.url, 'http://127.0.0.1');
    const file = resolve(decodeURIComponent(url.pathname));
    if (!file) {
      response.writeHead(403).end();
      return;
    }
    fs.readFile(file, (error, data) => {
      if (error) {
        response.writeHead(404, { 'Content-Type': 'text/plain' }).end(`not found: ${url.pathname}\n`);
        return;
      }
      response.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] ?? 'application/octet-stream',
                                'Cache-Control': 'no-store',
                                ...(isolated ? { 'Cross-Origin-Opener-Policy': 'same-origin',
                                                 'Cross-Origin-Embedder-Policy': 'require-corp' } : {}) });
      response.end(data);
    });
  });
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.stop = () => {
      server.close();
      server.closeAllConnections();
    };
    server.listen(port, '127.0.0.1', () => resolve(server));
  });
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const root = process.argv[2] ?? path.join(path.dirname(fileURLToPath(import.meta.url)), '..', 'build-web', 'site');
  const server = await startServer(root, Number(process.argv[3] ?? 8080));
  console.log(`serving ${path.resolve(root)} at http://127.0.0.1:${server.address().port}/  (Ctrl+C stops)`);
}
