// A job in a link (README, "A job in a link"): `#job=` and the job's JSON compressed with deflate-raw
// (RFC 1951, the browser's CompressionStream('deflate-raw')) in base64url without padding
// (RFC 4648 §5); or `?job=URL`, a job JSON on the same site, with the data files it names by a
// path relative to it. The data files a job holds (scattered points, STEP, grids) travel in the
// link while the link stays within MAX_LINK_CHARS; past that their text is left out and the
// caller says which file must be sent beside the link. Every way a link can be wrong (too long,
// not base64url, cut short, not deflate, not JSON, too large once inflated, another site, a
// missing file) is a LinkError with a message saying which, never an exception of the browser.

/** The longest link the page makes with the data files in it, characters: chat tools and
 * mail clients cut or refuse longer ones. */
export const MAX_LINK_CHARS = 16_384;

/** The longest fragment the page reads, characters (a link this long is not one it made). */
export const MAX_FRAGMENT_CHARS = 1 << 20;

/** The largest job the page reads from a link or from `?job=`, bytes once inflated: a job with
 * its data files inline. */
export const MAX_JOB_BYTES = 64 << 20;

/** The job format this page writes (the core's `job::format::FORMAT`). */
export const FORMAT = 1;

/** A link that cannot be read; `message` says why in the reader's terms. */
export class LinkError extends Error {}

/** base64url without padding of `bytes`. */
export function toBase64url(bytes) {
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary).replaceAll('+', '-').replaceAll('/', '_').replace(/=+$/, '');
}

/** The bytes of base64url text (padding optional); a LinkError for any other character. */
export function fromBase64url(text) {
  const bad = /[^A-Za-z0-9_-]/.exec(text.replace(/=+$/, ''));
  if (bad) throw new LinkError(`the link's job has a character that base64url does not use (“${bad[0]}” at ${bad.index + 1}): the link was changed or cut`);
  if (text.length % 4 === 1) throw new LinkError('the link\'s job is cut short (its length is no whole number of bytes): copy the whole link');
  const binary = atob(text.replaceAll('-', '+').replaceAll('_', '/').replace(/=+$/, ''));
  return Uint8Array.from(binary, (c) => c.charCodeAt(0));
}

/** `text` compressed with deflate-raw. */
export async function deflate(text) {
  const stream = new Blob([text]).stream().pipeThrough(new CompressionStream('deflate-raw'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

/** The text of deflate-raw `bytes`, at most `limit` bytes of it. */
export async function inflate(bytes, limit = MAX_JOB_BYTES) {
  const reader = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate-raw')).getReader();
  const parts = [];
  let total = 0;
  try {
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      total += value.length;
      if (total > limit) {
        await reader.cancel();
        throw new LinkError(`the link's job inflates to more than ${limit / (1 << 20)} MiB: the page reads no larger job from a link`);
      }
      parts.push(value);
    }
  } catch (e) {
    if (e instanceof LinkError) throw e;
    throw new LinkError('the link\'s job is cut short or damaged (it does not inflate): copy the whole link again');
  }
  const all = new Uint8Array(total);
  let at = 0;
  for (const p of parts) {
    all.set(p, at);
    at += p.length;
  }
  try {
    return new TextDecoder('utf-8', { fatal: true }).decode(all);
  } catch {
    throw new LinkError('the link\'s job is not UTF-8 text: the link was changed');
  }
}

/** The job object of JSON `text` read from `where`; a LinkError when it is no JSON object. */
function parseJob(text, where) {
  let job;
  try {
    job = JSON.parse(text);
  } catch (e) {
    throw new LinkError(`${where} is not JSON: ${e.message}`);
  }
  if (job === null || typeof job !== 'object' || Array.isArray(job)) throw new LinkError(`${where} is not a job: a JSON object {…} is expected`);
  return job;
}

/** The data files of a job: every `{path?, text?}` object in it, with where it is. */
export function dataFiles(job) {
  const found = [];
  const walk = (v, path) => {
    if (v === null || typeof v !== 'object') return;
    if (Array.isArray(v)) {
      v.forEach((x, i) => walk(x, `${path}[${i}]`));
      return;
    }
    const keys = Object.keys(v);
    if (keys.length && keys.every((k) => k === 'path' || k === 'text') && keys.every((k) => typeof v[k] === 'string')) {
      found.push({ field: path, file: v });
      return;
    }
    for (const k of keys) walk(v[k], path ? `${path}.${k}` : k);
  };
  walk(job, '');
  return found;
}

/** The fragment of `job` (`job=…`, without `#`). */
export async function jobFragment(job) {
  return `job=${toBase64url(await deflate(JSON.stringify({ format: FORMAT, ...job })))}`;
}

/** A link to `job` on the page at `base` (its address without fragment): { url, left }, `left`
 * the data files left out to keep the link within MAX_LINK_CHARS ({field, name}). */
export async function shareLink(job, base) {
  const full = `${base}#${await jobFragment(job)}`;
  const files = dataFiles(job).filter((f) => f.file.text !== undefined);
  if (full.length <= MAX_LINK_CHARS || !files.length) return { url: full, left: [] };
  const lean = structuredClone(job);
  const left = [];
  for (const { field } of dataFiles(lean)) {
    const file = field.split(/\.|\[|\]/).filter(Boolean).reduce((o, k) => o[k], lean);
    if (file.text === undefined) continue;
    delete file.text;
    file.path ??= `${field.replaceAll(/\W+/g, '-')}.txt`;
    left.push({ field, name: file.path });
  }
  return { url: `${base}#${await jobFragment(lean)}`, left };
}

/** The job of a `#job=` fragment (with or without `#`). */
export async function jobFromFragment(fragment) {
  const text = fragment.replace(/^#/, '').slice('job='.length);
  if (fragment.length > MAX_FRAGMENT_CHARS) throw new LinkError(`the link is ${fragment.length} characters long: the page reads links of at most ${MAX_FRAGMENT_CHARS}`);
  if (!text) throw new LinkError('the link holds no job after #job=');
  return parseJob(await inflate(fromBase64url(text)), 'the link\'s job');
}

/** `url`'s text, at most `limit` bytes, from this site only. */
async function fetchText(url, what, limit = MAX_JOB_BYTES) {
  if (url.origin !== location.origin) throw new LinkError(`${what} ${url.href} is on another site: ?job= loads jobs from this site only`);
  let response;
  try {
    response = await fetch(url);
  } catch (e) {
    throw new LinkError(`${what} ${url.pathname} could not be loaded: ${e.message}`);
  }
  if (!response.ok) throw new LinkError(`${what} ${url.pathname} could not be loaded: ${response.status} ${response.statusText || 'error'}`);
  const size = Number(response.headers.get('content-length'));
  if (size > limit) throw new LinkError(`${what} ${url.pathname} is ${size} bytes: at most ${limit} are read`);
  const text = await response.text();
  if (text.length > limit) throw new LinkError(`${what} ${url.pathname} is larger than ${limit} bytes`);
  return text;
}

/** The job at `src` (resolved against `base`), with the data files it names by a relative path
 * read beside it (the path kept, as the command line does). */
export async function jobFromUrl(src, base = location.href) {
  let url;
  try {
    url = new URL(src, base);
  } catch {
    throw new LinkError(`?job=${src} is not an address`);
  }
  const job = parseJob(await fetchText(url, 'the job'), `the job ${url.pathname}`);
  for (const { file } of dataFiles(job)) {
    if (file.text !== undefined || !file.path) continue;
    file.text = await fetchText(new URL(file.path, url), 'its data file', 256 << 20);
  }
  return job;
}

/** The job a page address carries: `{ job, source }` (`source` "link" or the `?job=` value),
 * or null when it carries none. */
export async function jobFromLocation(loc = location) {
  if (loc.hash.startsWith('#job=')) return { job: await jobFromFragment(loc.hash), source: 'link' };
  const src = new URLSearchParams(loc.search).get('job');
  if (src) return { job: await jobFromUrl(src, loc.href), source: src };
  return null;
}

/** The problem of a job's `format` for this page, or null (absent or 1). */
export function formatProblem(job) {
  if (job.format === undefined || job.format === FORMAT) return null;
  return `format = ${JSON.stringify(job.format)}: this spiralcam reads job format ${FORMAT} only: the job was written by a newer spiralcam (or is not a spiralcam job)`;
}
