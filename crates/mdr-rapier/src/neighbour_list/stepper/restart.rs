//! Restart: the neighbour-list state out of a stepper and back into one built the same way.

use super::*;

impl<N, T, D, R, B> NeighbourListStepper<N, T, D, R, B>
where
    N: NormalModel,
    T: TangentialModel,
    D: DampingModel,
    R: RollingModel,
    B: WorkBooks,
    N::Law: Clone,
    T::Law: Clone,
    D::Law: Clone,
    R::Law: Clone,
{
    /// Copy of the neighbour-list state (see [`NeighbourListState`]); take it between two steps.
    pub fn export_lists(&self) -> NeighbourListState<NeighbourListHistory<N, T, R, B>> {
        let p = &self.pairs;
        let sp = &self.surface_pairs;
        NeighbourListState {
            built_at: self.built_at.clone(),
            max_displacement: self.max_displacement,
            surface_poses: self.surfaces.iter().map(|s| s.pose_at_build).collect(),
            rebuilds: self.rebuilds,
            pairs: (0..p.len()).map(|k| (p.i[k], p.j[k], p.image[k])).collect(),
            pair_active: p.active.clone(),
            pair_history: p.history.clone(),
            surface_pairs: (0..sp.len())
                .map(|k| (sp.particle[k], sp.surface[k]))
                .collect(),
            surface_active: sp.active.clone(),
            surface_history: sp.history.clone(),
        }
    }

    /// Restore a state from [`NeighbourListStepper::export_lists`] of a stepper built the same way
    /// (same particles, surfaces and laws), with the particles' positions and velocities of the
    /// same step already set. Binds the laws; the lists are used as they are, without a build.
    pub fn import_lists(
        &mut self,
        world: &PhysicsWorld,
        state: NeighbourListState<NeighbourListHistory<N, T, R, B>>,
    ) -> Result<()> {
        let n = self.particles.len();
        let nsurf = self.surfaces.len();
        let mismatch = |what: String| Err(CouplingError::StateMismatch(what));
        if state.built_at.len() != n {
            return mismatch(format!(
                "it holds {} particles, the stepper {n}",
                state.built_at.len()
            ));
        }
        if state.surface_poses.len() != nsurf {
            return mismatch(format!(
                "it holds {} surfaces, the stepper {nsurf}",
                state.surface_poses.len()
            ));
        }
        let m = state.pairs.len();
        if state.pair_active.len() != m || state.pair_history.len() != m {
            return mismatch("its sphere-pair arrays differ in length".to_owned());
        }
        let ms = state.surface_pairs.len();
        if state.surface_active.len() != ms || state.surface_history.len() != ms {
            return mismatch("its surface-pair arrays differ in length".to_owned());
        }
        let codes = self.boundary.offsets().len();
        let pairs_ok = state
            .pairs
            .iter()
            .all(|&(i, j, c)| i < j && (j as usize) < n && (c as usize) < codes)
            && state.pairs.windows(2).all(|w| w[0] < w[1]);
        if !pairs_ok {
            return mismatch("its sphere pairs are out of range or not sorted".to_owned());
        }
        let surface_ok = state
            .surface_pairs
            .iter()
            .all(|&(i, s)| (i as usize) < n && (s as usize) < nsurf)
            && state.surface_pairs.windows(2).all(|w| w[0] < w[1]);
        if !surface_ok {
            return mismatch("its surface pairs are out of range or not sorted".to_owned());
        }
        self.bind_laws(&world.bodies)?;
        self.built_at = state.built_at;
        self.max_displacement = state.max_displacement;
        self.rebuilds = state.rebuilds;
        for (s, pose) in self.surfaces.iter_mut().zip(&state.surface_poses) {
            s.pose_at_build = *pose;
        }
        let mut pairs = PairList {
            i: state.pairs.iter().map(|p| p.0).collect(),
            j: state.pairs.iter().map(|p| p.1).collect(),
            image: state.pairs.iter().map(|p| p.2).collect(),
            active: state.pair_active,
            history: state.pair_history,
            ..PairList::default()
        };
        pairs.reindex(n);
        self.pairs = pairs;
        self.old_pairs = PairList::default();
        let mut start = vec![0u32; n + 1];
        for &(i, _) in &state.surface_pairs {
            start[i as usize + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let sp = SurfacePairs {
            particle: state.surface_pairs.iter().map(|p| p.0).collect(),
            surface: state.surface_pairs.iter().map(|p| p.1).collect(),
            active: state.surface_active,
            history: state.surface_history,
            wrench: vec![PairWrench::default(); ms],
            contact: vec![SurfaceContact::default(); ms],
            start,
        };
        self.surface_pairs = sp;
        self.old_surface_pairs = SurfacePairs::default();
        self.needs_build = false;
        self.pending = None;
        Ok(())
    }
}
