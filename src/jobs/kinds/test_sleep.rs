//! `test_sleep`: a deliberately slow kind, compiled only with the `test-kinds` feature (enabled
//! by the crate's own dev-dependency), for cancellation, timeout, panic and restart tests.

use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::{Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use utoipa::ToSchema;

pub struct TestSleep;

/// Sleep in 10 ms steps, polling for cancellation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TestSleepSpec {
    /// Seconds to sleep.
    pub seconds: f64,
    /// Panic instead of finishing.
    #[serde(default)]
    pub panic: bool,
    /// Any value: lets tests submit distinct specs.
    #[serde(default)]
    pub nonce: u64,
}

#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct TestSleepResult {
    pub slept_seconds: f64,
    pub table: StepTable,
}

/// Columnar table: one row per 10 ms step.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct StepTable {
    pub step: Vec<u32>,
}

impl Kind for TestSleep {
    const NAME: &'static str = "test_sleep";
    const SOLVER_VERSION: &'static str = "test-1";
    const DESCRIPTION: &'static str = "Test builds only: sleeps, polling for cancellation.";
    const TABLES: &'static [&'static str] = &["table"];
    type Spec = TestSleepSpec;
    type Output = TestSleepResult;

    fn example() -> Value {
        json!({"seconds": 0.05})
    }

    fn validate(spec: &TestSleepSpec, _limits: &Limits, v: &mut Validation) {
        v.in_range("/seconds", spec.seconds, 0.0, 3600.0);
    }

    fn cost(spec: &TestSleepSpec) -> Cost {
        // It holds a worker for its seconds (sleeping, not computing).
        Cost::new(spec.seconds, 0.0).work_at("/seconds", format!("sleeping {} s", spec.seconds))
    }

    fn solve(spec: &TestSleepSpec, observer: &dyn Observer) -> Result<TestSleepResult, SolveError> {
        let start = std::time::Instant::now();
        let mut steps = Vec::new();
        let mut i = 0;
        while start.elapsed().as_secs_f64() < spec.seconds {
            observer.check()?;
            observer.progress(start.elapsed().as_secs_f64() / spec.seconds, "sleeping");
            if spec.panic && start.elapsed().as_secs_f64() > 0.5 * spec.seconds {
                panic!("test_sleep was asked to panic");
            }
            std::thread::sleep(std::time::Duration::from_millis(10));
            steps.push(i);
            i += 1;
        }
        if spec.panic {
            panic!("test_sleep was asked to panic");
        }
        Ok(TestSleepResult { slept_seconds: start.elapsed().as_secs_f64(), table: StepTable { step: steps } })
    }
}
