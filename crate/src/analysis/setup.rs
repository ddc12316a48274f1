//! Set-up geometry (placeholder).
