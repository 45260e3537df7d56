//! Surface geometry shared by the films and the systems that use them: roller crowns (seed 000
//! Table 1 and eq. 3). It sits below the film models (`film`, `ehl`) and the roller, so each of
//! them can take a crown without importing another.

pub mod crown;

pub use crown::{Crown, CrownProfile, CrownedContact};
