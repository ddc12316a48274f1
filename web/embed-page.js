// index.html?embed: the page as one <spiralcam-viewer> filling the window, for hosts that embed
// it in an iframe. The job comes from the address (#job=… or ?job=URL, as for the page) or from
// the parent: `{type: "spiralcam:load", job}` posted to the frame loads and plans `job`, and each
// plan is answered `{type: "spiralcam:planned", report}` (or `{type: "spiralcam:error",
// message}`). Messages are accepted from this site's origin and from the origins named by
// `allow` parameters (`index.html?embed&allow=https://docs.example.com`); others are ignored.

import { offlineCopy } from './offline.js';
import './spiralcam-viewer.js';

/** Replaces the page's body with the viewer and answers its parent. */
export function startEmbed() {
  const params = new URLSearchParams(location.search);
  const allowed = new Set([location.origin, ...params.getAll('allow')]);
  const status = (window.spiralcam = { state: 'loading', embed: true, ignored: 0, report: null, error: null });
  const setState = (s) => {
    status.state = s;
    document.body.dataset.state = s;
  };
  const viewer = document.createElement('spiralcam-viewer');
  viewer.style.cssText = 'height: 100vh; border: 0; border-radius: 0;';
  for (const a of ['controls', 'downloads', 'max-points']) if (params.has(a)) viewer.setAttribute(a, params.get(a));
  viewer.setAttribute('app', new URL('../index.html', import.meta.url).pathname);
  document.body.className = 'embed';
  document.body.style.cssText = 'margin: 0; height: 100vh; display: block;';
  document.body.replaceChildren(viewer);

  // Answers go to the origin that asked last; before any ask, to a referring host allowed.
  let answerTo = null;
  try {
    const referrer = document.referrer && new URL(document.referrer).origin;
    if (referrer && allowed.has(referrer)) answerTo = referrer;
  } catch {
    // No usable referrer: answers wait for a message.
  }
  const answer = (message) => {
    if (window.parent !== window && answerTo) window.parent.postMessage(message, answerTo);
  };
  viewer.addEventListener('spiralcam:planned', (e) => {
    status.report = e.detail.report;
    setState('done');
    answer({ type: 'spiralcam:planned', report: e.detail.report });
  });
  viewer.addEventListener('spiralcam:error', (e) => {
    status.error = e.detail.message;
    setState('error');
    answer({ type: 'spiralcam:error', message: e.detail.message });
  });
  window.addEventListener('message', (e) => {
    if (!allowed.has(e.origin) || e.data?.type !== 'spiralcam:load') {
      if (e.data?.type?.startsWith?.('spiralcam:')) status.ignored += 1;
      return;
    }
    answerTo = e.origin;
    setState('planning');
    viewer.setJob(e.data.job);
  });

  offlineCopy(status, () => {});
  if (location.hash.startsWith('#job=')) viewer.setAttribute('job', location.hash);
  else if (params.get('job')) viewer.setAttribute('src', new URL(params.get('job'), location.href).href);
  else setState('waiting');
}
