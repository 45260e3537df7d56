//! Every integration test in one binary: the crate is linked once, not once per file.
//!
//! Each module is one subject. HTTP tests start the real server on a loopback port with a
//! temporary SQLite file (`common`); validation tests run job kinds in-process (`in_process`);
//! `*_stability` are the property tests (their failures are saved beside them in
//! `*.proptest-regressions` and replayed first).

#[macro_use]
mod common;
mod in_process;

mod accuracy_targets;
mod cam_stability;
mod cam_optimisation;
mod cam_synthesis;
mod cam_validation;
mod ehl_stability;
mod ehl_validation;
mod ehl_2d;
mod ehl_2d_cam;
mod ehl_2d_dry;
mod ehl_2d_fields;
mod ehl_2d_transient;
mod examples_run;
mod fan_out;
mod fan_out_faults;
mod fan_out_sqlite;
mod house;
mod house_plan;
mod http_api;
mod job_limits;
mod journal_dynamics;
mod journal_examples;
mod journal_kinds;
mod journal_stability;
mod journal_validation;
mod micro_slip_map;
mod mixed_lubrication;
mod multi_instance;
mod openapi_drift;
mod pin_finite;
mod rough_stability;
mod rough_validation;
mod browser;
mod plots;
mod readable_results;
mod reliability;
mod restart_recovery;
mod storage_faults;
mod seed003_fit;
mod service_units;
mod sweep_api;
mod thermal_ehl;
mod thermal_finite_cam;
mod valvetrain_http;
mod valvetrain_lever;
mod valvetrain_springs;
mod valvetrain_progressive;
mod polydyne_correction;
mod valvetrain_stability;
mod valvetrain_validation;
mod wear_stability;
mod wear_validation;
