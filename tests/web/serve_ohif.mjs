// Serves OHIF's published build (tests/web/ohif/, from install_ohif.sh) as the single-page app it
// is: a path that is not a file (/viewer, /segmentation, ...) gets index.html, and /app-config.js
// comes from the file given, so one build serves any soiqd. Node's standard library only: the
// viewer test and `make viewer` need nothing installed beyond OHIF itself.
//   node serve_ohif.mjs --config APP_CONFIG_JS [--listen 127.0.0.1:PORT] [--port-file FILE] [--dist DIR]
// PORT 0 (the default) takes a free port; the bound one is printed and written to --port-file.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const options = { listen: '127.0.0.1:0', dist: path.join(path.dirname(fileURLToPath(import.meta.url)), 'ohif') };
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i += 2) {
  const name = argv[i].replace(/^--/, '');
  if (!['config', 'listen', 'port-file', 'dist'].includes(name) || argv[i + 1] === undefined) {
    console.error(`serve_ohif: unknown or incomplete argument '${argv[i]}'`);
    process.exit(2);
  }
  options[name] = argv[i + 1];
}
if (!options.config) {
  console.error('serve_ohif: --config APP_CONFIG_JS is required (OHIF needs its data source)');
  process.exit(2);
}
const dist = path.resolve(options.dist);
if (!fs.existsSync(path.join(dist, 'index.html'))) {
  console.error(`serve_ohif: no OHIF build in ${dist}: tests/web/install_ohif.sh installs it`);
  process.exit(1);
}
const config = path.resolve(options.config);
const colon = options.listen.lastIndexOf(':');
const host = options.listen.slice(0, colon);
const port = Number(options.listen.slice(colon + 1));

const types = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.map': 'application/json',
  '.wasm': 'application/wasm', // WebAssembly.instantiateStreaming refuses any other type
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.ico': 'image/x-icon',
  '.woff': 'font/woff',
  '.woff2': 'font/woff2',
  '.txt': 'text/plain; charset=utf-8',
};

function send(res, status, file, method) {
  fs.stat(file, (error, stat) => {
    if (error) {
      res.writeHead(500, { 'Content-Type': 'text/plain' });
      res.end(`serve_ohif: ${error.message}\n`);
      return;
    }
    // OHIF's bundles carry their hash in the name; index.html and app-config.js do not, and must
    // not be cached across runs pointing at different soiqds.
    res.writeHead(status, {
      'Content-Type': types[path.extname(file)] || 'application/octet-stream',
      'Content-Length': stat.size,
      'Cache-Control': 'no-cache',
    });
    if (method === 'HEAD') res.end();
    else fs.createReadStream(file).pipe(res);
  });
}

const server = http.createServer((req, res) => {
  if (req.method !== 'GET' && req.method !== 'HEAD') {
    res.writeHead(405, { Allow: 'GET, HEAD' });
    res.end();
    return;
  }
  let rel;
  try {
    rel = decodeURIComponent(new URL(req.url, 'http://x').pathname);
  } catch {
    res.writeHead(400);
    res.end();
    return;
  }
  if (rel === '/app-config.js') return send(res, 200, config, req.method);
  const file = path.join(dist, rel);
  // path.join resolves '..': anything that leaves dist/ is not served, only the app.
  const inside = file.startsWith(dist + path.sep);
  fs.stat(file, (error, stat) => {
    if (inside && !error && stat.isFile()) send(res, 200, file, req.method);
    else send(res, 200, path.join(dist, 'index.html'), req.method); // the app's own routes
  });
});

server.listen(port, host, () => {
  const bound = server.address().port;
  if (options['port-file']) {
    // Written whole then renamed: a reader polling the file never sees half a number.
    fs.writeFileSync(`${options['port-file']}.tmp`, `${bound}\n`);
    fs.renameSync(`${options['port-file']}.tmp`, options['port-file']);
  }
  console.log(`serve_ohif: OHIF on http://${host}:${bound}/ (app-config.js: ${config})`);
});
server.on('error', (error) => {
  console.error(`serve_ohif: cannot listen on ${options.listen}: ${error.message}`);
  process.exit(1);
});
// Ctrl-C or the test's kill: nothing to flush, and an open keep-alive connection must not hold it.
for (const signal of ['SIGINT', 'SIGTERM']) process.on(signal, () => process.exit(0));
