// Pointer and wheel gestures on a canvas turned into the 3-D viewer's camera moves: drag to
// orbit, right-drag or shift-drag to pan, wheel or pinch to zoom, double-click to reset. Used by
// the page (web/app.js) and the embeddable viewer (web/spiralcam-viewer.js).

/** Pointer and wheel gestures on the canvas → viewer camera. */
export function bindGestures(canvas, viewer, redraw) {
  const pointers = new Map();
  let pinch = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => {
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, button: e.button, shift: e.shiftKey });
  });
  const end = (e) => {
    pointers.delete(e.pointerId);
    pinch = null;
  };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('pointermove', (e) => {
    const p = pointers.get(e.pointerId);
    if (!p) return;
    const dx = e.clientX - p.x;
    const dy = e.clientY - p.y;
    p.x = e.clientX;
    p.y = e.clientY;
    if (pointers.size === 2) {
      const [a, b] = [...pointers.values()];
      const d = Math.hypot(a.x - b.x, a.y - b.y);
      if (pinch) viewer.zoom(d / pinch);
      pinch = d;
      viewer.pan(dx / 2, dy / 2);
    } else if (p.button === 2 || p.button === 1 || p.shift) {
      viewer.pan(dx, dy);
    } else {
      viewer.orbit(dx, dy);
    }
    redraw();
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    viewer.zoom(Math.exp(-e.deltaY * 0.0015));
    redraw();
  }, { passive: false });
  canvas.addEventListener('dblclick', () => {
    viewer.reset_view();
    redraw();
  });
}
