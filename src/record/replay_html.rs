//! The replay page (`berry-evolve replay --html`).
