use super::*;

impl Workspace {
    pub(crate) fn new() -> Self {
        Workspace {
            n: 0,
            v: Fields::default(),
            trial: Fields::default(),
            c: Vec::new(),
            ph: Vec::new(),
            ph_trial: Vec::new(),
            dp: Vec::new(),
            dh: Vec::new(),
            p_trial: Vec::new(),
            sol: Vec::new(),
            sys: System::default(),
            factor: Factor::empty(),
            krylov: Krylov::default(),
            stats: SolverStats::default(),
        }
    }

    /// Size every buffer for `n` nodes (keeps the kept factors when `n` is unchanged).
    pub(super) fn ensure(&mut self, n: usize) {
        if self.n == n {
            return;
        }
        self.n = n;
        let dim = n - 1; // n − 2 interior pressures and H0
        let z = vec![0.0; n];
        self.v = Fields::new(n);
        self.trial = Fields::new(n);
        self.c = z.clone();
        self.ph = z.clone();
        self.ph_trial = z.clone();
        self.dp = z.clone();
        self.dh = z.clone();
        self.p_trial = z.clone();
        self.sol = vec![0.0; dim];
        self.sys = System {
            aa: std::array::from_fn(|_| z.clone()),
            cg: std::array::from_fn(|_| z.clone()),
            gsum: z.clone(),
            rhs: vec![0.0; dim],
        };
        self.factor.resize(dim);
        let k = GMRES_MAX + 1;
        self.krylov = Krylov {
            basis: vec![0.0; k * dim],
            hess: vec![0.0; k * GMRES_MAX],
            cs: vec![0.0; GMRES_MAX],
            sn: vec![0.0; GMRES_MAX],
            g: vec![0.0; k],
            w: vec![0.0; dim],
            z: vec![0.0; dim],
            zs: vec![0.0; GMRES_MAX * dim],
            dp: vec![0.0; n + 4],
            dh: vec![0.0; n + 4],
            defl: vec![0.0; n],
        };
    }
}

/// Solve the Newton system in `ws.sys` into `ws.sol` with the relative linear residual `eta`
/// (the forcing term, [`forcing`]): GMRES with the kept factors when they belong to this grid,
/// else (or when GMRES stalls) a fresh factorisation; after more than [`GMRES_REFRESH`] GMRES
/// iterations the next step factorises afresh. `false` when the Jacobian is singular.
pub(super) fn linear_solve(ws: &mut Workspace, grid: &Grid, eta: f64) -> bool {
    if ws.factor.grid_id == grid.id {
        if let Some(it) = gmres(&ws.sys, grid, &mut ws.factor, &mut ws.krylov, &mut ws.sol, eta) {
            ws.stats.gmres_iterations += it as u64;
            // The kept factors have drifted from the Jacobian: refresh them at the next step.
            if it > GMRES_REFRESH {
                ws.factor.grid_id = 0;
            }
            return true;
        }
        ws.stats.gmres_iterations += GMRES_MAX as u64;
    }
    let mut lu = std::mem::take(&mut ws.factor.lu);
    assemble(&ws.sys, grid, &mut ws.krylov, &mut lu);
    ws.factor.lu = lu;
    ws.stats.factorisations += 1;
    if !ws.factor.factorise(grid.id) {
        return false;
    }
    ws.sol.copy_from_slice(&ws.sys.rhs);
    let mut sol = std::mem::take(&mut ws.sol);
    ws.factor.solve(&mut sol);
    ws.sol = sol;
    true
}
