//! Integration tests of spiralcam: see `tests/tests/`.
