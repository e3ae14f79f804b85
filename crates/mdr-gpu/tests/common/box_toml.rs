//! The scene file of the GPU tests' box scenes, written in one place: spheres from CSV files in
//! a box wall (`kind = "box"`), gravity 9.81 m/s² along −z.

/// A box scene's TOML: its `[run]` table, materials, contact model, particle files and box.
pub struct BoxToml<'a> {
    /// `[run]`: name, duration (s), time step (s), speed bound (m/s), frame interval (s).
    pub name: &'a str,
    pub duration_s: f64,
    pub dt_s: f64,
    pub max_speed_m_per_s: f64,
    pub output_interval_s: f64,
    /// Further `[run]` lines (`energy_interval_s`, a guard …).
    pub run: &'a str,
    /// `[[material]]` entries: name, Young's modulus (Pa), Poisson ratio, density (kg/m³) and
    /// further lines.
    pub materials: &'a [(&'a str, f64, f64, f64, &'a str)],
    /// The `[contact]` lines.
    pub contact: &'a str,
    /// `[[particles]]` entries: material and CSV file.
    pub particles: &'a [(&'a str, &'a str)],
    /// The box: its material, inside `[min_m, max_m]` (m), slab thickness (m), open top.
    pub wall_material: &'a str,
    pub min_m: [f64; 3],
    pub max_m: [f64; 3],
    pub thickness_m: f64,
    pub open_top: bool,
}

impl BoxToml<'_> {
    /// The scene file's text (every number as Rust writes it back, the same double).
    pub fn text(&self) -> String {
        let mut text = format!(
            "[run]\nname = \"{}\"\nduration_s = {:?}\ndt_s = {:?}\nmax_speed_m_per_s = {:?}\n\
             output_interval_s = {:?}\n{}\n\n\
             [gravity]\nacceleration_m_per_s2 = [0.0, 0.0, -9.81]\n\n",
            self.name,
            self.duration_s,
            self.dt_s,
            self.max_speed_m_per_s,
            self.output_interval_s,
            self.run
        );
        for (name, youngs, poisson, density, extra) in self.materials {
            text.push_str(&format!(
                "[[material]]\nname = \"{name}\"\nyoungs_pa = {youngs:?}\n\
                 poisson_ratio = {poisson:?}\ndensity_kg_per_m3 = {density:?}\n{extra}\n\n"
            ));
        }
        text.push_str(&format!("[contact]\n{}\n\n", self.contact));
        for (material, file) in self.particles {
            text.push_str(&format!(
                "[[particles]]\nmaterial = \"{material}\"\nplacement = \"csv\"\nfile = \"{file}\"\n\n"
            ));
        }
        text.push_str(&format!(
            "[[walls]]\nkind = \"box\"\nmaterial = \"{}\"\nmin_m = {:?}\nmax_m = {:?}\n\
             thickness_m = {:?}\nopen_top = {}\n",
            self.wall_material, self.min_m, self.max_m, self.thickness_m, self.open_top
        ));
        text
    }
}
