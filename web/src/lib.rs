//! spiralcam in the browser (placeholder while the core is built).
