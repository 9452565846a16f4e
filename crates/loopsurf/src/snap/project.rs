//! Local projection from a guess (filled in by the projection work).
