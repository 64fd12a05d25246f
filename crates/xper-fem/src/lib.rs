//! Finite elements (placeholder, being written).
