//! The arguments that name a configuration of a pack, shared by `validate` and `render`: the
//! profile, single option values, the dimension and the loader
//! ([`tidepack_loader::Configuration`]).

use clap::Args;
use tidepack_loader::{Configuration, Dimension, Loader};
use tidepack_loader::option_space::parse_assignments;

#[derive(Args, Clone, Debug)]
pub struct ConfigurationArgs {
    /// Profile of shaders.properties whose values to use instead of the defaults.
    #[arg(long)]
    pub profile: Option<String>,
    /// Set one option (repeatable, after the profile): `--set SSR_STEPS=24`, `--set FOAM=off`.
    #[arg(long = "set", value_name = "OPTION=VALUE")]
    pub set: Vec<String>,
    /// The dimension whose world folder's programs run: overworld, nether, end or a folder
    /// name such as world7 (default: the overworld; `validate` checks every world folder).
    #[arg(long, value_parser = Dimension::parse)]
    pub dimension: Option<Dimension>,
    /// The loader: optifine-1.21, optifine-1.16.5, optifine-1.12.2, optifine-1.8.9 or iris
    /// (docs/loaders.md says what differs).
    #[arg(long, default_value_t = Loader::default())]
    pub loader: Loader,
    /// Distant Horizons installed beside Iris (needs --loader iris): DISTANT_HORIZONS is
    /// defined, and Iris runs the pack's dh_* programs.
    #[arg(long)]
    pub distant_horizons: bool,
}

impl ConfigurationArgs {
    /// The configuration the arguments name; a malformed `--set` is an error naming it.
    pub fn configuration(&self) -> Result<Configuration, String> {
        if self.distant_horizons && self.loader != Loader::Iris {
            return Err("--distant-horizons needs --loader iris: Distant Horizons' programs run only through Iris".into());
        }
        Ok(Configuration {
            profile: self.profile.clone(),
            options: parse_assignments(&self.set)?,
            dimension: self.dimension.clone().unwrap_or_default(),
            loader: self.loader,
            distant_horizons: self.distant_horizons,
        })
    }
}
