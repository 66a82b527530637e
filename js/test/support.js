// Node-side helpers of the browser tests: a static server over the repository, headless
// Chromium (WebGL through SwiftShader), and raster-sink's references via `cargo xtask truth`.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { extname, join, normalize, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { PNG } from 'pngjs';

export const ROOT = resolve(fileURLToPath(new URL('../..', import.meta.url)));

const TYPES = { '.js': 'text/javascript', '.mjs': 'text/javascript', '.html': 'text/html', '.wasm': 'application/wasm', '.obj': 'text/plain', '.json': 'application/json' };

/** A static HTTP server over the repository root, on a free port. */
export async function serve() {
  const server = createServer((req, res) => {
    const path = normalize(decodeURIComponent(new URL(req.url, 'http://x').pathname));
    const file = join(ROOT, path);
    if (!file.startsWith(ROOT) || !existsSync(file)) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream' });
    res.end(readFileSync(file));
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  return { server, origin: `http://127.0.0.1:${server.address().port}` };
}

/** Debian's Chromium (or $CHROMIUM), headless, WebGL by SwiftShader, sRGB output. */
export async function chromium() {
  const { chromium: launcher } = await import('playwright-core');
  const executablePath = process.env.CHROMIUM ?? ['/usr/bin/chromium', '/usr/bin/chromium-browser'].find(existsSync);
  if (!executablePath) throw new Error('browser tests need Chromium: apt-get install chromium, or set CHROMIUM');
  return launcher.launch({
    executablePath,
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--force-color-profile=srgb', '--no-sandbox'],
  });
}

/** raster-sink's references for a scene (see `cargo xtask truth --help`). */
export function truth(scene) {
  const dir = mkdtempSync(join(tmpdir(), 'facesort-truth-'));
  writeFileSync(join(dir, 'scene.json'), JSON.stringify(scene));
  execFileSync('cargo', ['run', '--quiet', '-p', 'xtask', '--', 'truth', '--scene', join(dir, 'scene.json'), '--out', dir], { cwd: ROOT, stdio: ['ignore', 'inherit', 'inherit'] });
  const read = (name) => (existsSync(join(dir, name)) ? readFileSync(join(dir, name)) : null);
  const ids = read('ids.bin');
  return {
    ids: new Uint32Array(ids.buffer, ids.byteOffset, ids.length / 4),
    idsMask: read('ids_mask.bin'),
    composite: read('composite.rgba'),
    compositeMask: read('composite_mask.bin'),
  };
}

export const bytes = (b64) => new Uint8Array(Buffer.from(b64, 'base64'));

/** The ID of each pixel of an RGBA image. */
export function idsOf(rgba) {
  const out = new Uint32Array(rgba.length / 4);
  for (let i = 0; i < out.length; i++) out[i] = (rgba[4 * i] << 16) | (rgba[4 * i + 1] << 8) | rgba[4 * i + 2];
  return out;
}

/** An SVG document as Chromium draws it on a page (its own tab, one pixel per unit, on
 * black), RGBA from the top-left. */
export async function rasterise(browser, svg, width, height) {
  const page = await browser.newPage({ viewport: { width, height }, deviceScaleFactor: 1 });
  try {
    await page.setContent(`<!doctype html><html><body style="margin:0;background:#000">${svg}</body></html>`);
    const png = PNG.sync.read(await page.screenshot({ clip: { x: 0, y: 0, width, height } }));
    return new Uint8Array(png.data.buffer, png.data.byteOffset, png.data.length);
  } finally {
    await page.close();
  }
}
