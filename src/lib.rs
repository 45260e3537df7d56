//! tribod: an HTTP calculation service for valve-train and bearing tribology.
//!
//! Data flows one way: HTTP → validated spec → queue (SQLite row) → worker (rayon) → physics →
//! result → SQLite → HTTP. `physics` never sees the database or the web; `api` never runs a solver.

pub mod api;
pub mod jobs;
pub mod metrics;
pub use tribod_physics as physics;
pub mod plots;
pub mod problem;
pub mod server;
pub mod store;
pub mod web;
