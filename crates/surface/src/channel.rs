//! Channels of a multi-channel instrument file: an AFM scan stores several images of the same
//! field (height, phase, amplitude, trace and retrace). A reader lists them as [`Channel`]s,
//! reads the one a [`ChannelSelector`] names, and by default the first height channel, as
//! SurfaceTopography does.

use crate::error::{Result, SurfaceError};
use std::fmt;
use std::path::Path;
use std::str::FromStr;

/// One image stored in a file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Channel {
    /// 0-based position among the file's channels.
    pub index: usize,
    /// Name as the file writes it ("Height", "ZSensor", "Phase", ...).
    pub name: String,
    /// Unit of the channel's values as the file writes it ("nm", "º", "V"), when it states one.
    pub unit: Option<String>,
    /// Whether the channel holds heights (a length), which gonio can read as a height map.
    pub is_height: bool,
    /// Why the channel cannot be read, when it cannot (a scale gonio cannot interpret, say):
    /// the file's other channels read all the same, and asking for this one is an error that
    /// says this.
    pub problem: Option<String>,
}

impl fmt::Display for Channel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} '{}'", self.index, self.name)?;
        if let Some(unit) = &self.unit {
            write!(f, " ({unit})")?;
        }
        Ok(())
    }
}

/// Which channel of a file to read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ChannelSelector {
    /// The channel of this name, compared without regard to case; the first one when several
    /// channels share the name.
    Name(String),
    /// The channel at this 0-based index.
    Index(usize),
}

impl FromStr for ChannelSelector {
    type Err = std::convert::Infallible;

    /// A number is an index, anything else a name.
    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        Ok(match s.trim().parse::<usize>() {
            Ok(index) => ChannelSelector::Index(index),
            Err(_) => ChannelSelector::Name(s.trim().to_string()),
        })
    }
}

impl fmt::Display for ChannelSelector {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ChannelSelector::Name(name) => write!(f, "'{name}'"),
            ChannelSelector::Index(index) => write!(f, "index {index}"),
        }
    }
}

/// The index of the channel to read among `channels`: the one `selector` names, or by default
/// the first height channel that can be read. Errors name the file and list its channels when the
/// selector matches none, and say why when the channel picked cannot be read or does not hold
/// heights.
pub(crate) fn select(
    path: &Path,
    format: &'static str,
    channels: &[Channel],
    selector: Option<&ChannelSelector>,
) -> Result<usize> {
    let listing = || {
        channels
            .iter()
            .map(Channel::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let err = |message: String| SurfaceError::format(path, format, message);
    let found = match selector {
        None => channels
            .iter()
            .find(|c| c.is_height && c.problem.is_none())
            .ok_or_else(|| {
                err(format!(
                    "no height channel among the file's channels: {}",
                    listing()
                ))
            })?,
        Some(wanted) => channels
            .iter()
            .find(|c| match wanted {
                ChannelSelector::Name(name) => c.name.eq_ignore_ascii_case(name),
                ChannelSelector::Index(index) => c.index == *index,
            })
            .ok_or_else(|| {
                err(format!(
                    "no channel {wanted}; the file's channels are: {}",
                    listing()
                ))
            })?,
    };
    if let Some(problem) = &found.problem {
        return Err(err(format!(
            "channel {found} cannot be read: {problem}; the file's channels are: {}",
            listing()
        )));
    }
    if !found.is_height {
        return Err(err(format!(
            "channel {found} does not hold heights; the file's channels are: {}",
            listing()
        )));
    }
    Ok(found.index)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channels() -> Vec<Channel> {
        let c = |index, name: &str, unit: &str, is_height| Channel {
            index,
            name: name.into(),
            unit: Some(unit.into()),
            is_height,
            problem: None,
        };
        vec![
            c(0, "Phase", "º", false),
            c(1, "Height", "nm", true),
            c(2, "ZSensor", "nm", true),
        ]
    }

    #[test]
    fn default_is_the_first_height_channel() {
        let p = Path::new("a.spm");
        assert_eq!(select(p, "t", &channels(), None).unwrap(), 1);
        let by_name = ChannelSelector::Name("zsensor".into());
        assert_eq!(select(p, "t", &channels(), Some(&by_name)).unwrap(), 2);
        assert_eq!(
            select(p, "t", &channels(), Some(&ChannelSelector::Index(2))).unwrap(),
            2
        );
    }

    #[test]
    fn unknown_or_non_height_channels_are_errors_listing_the_channels() {
        let p = Path::new("a.spm");
        let e = select(p, "t", &channels(), Some(&"Friction".parse().unwrap()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("a.spm") && e.contains("'Friction'"), "{e}");
        assert!(
            e.contains("0 'Phase' (º), 1 'Height' (nm), 2 'ZSensor' (nm)"),
            "{e}"
        );
        let e = select(p, "t", &channels(), Some(&"7".parse().unwrap()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no channel index 7"), "{e}");
        let e = select(p, "t", &channels(), Some(&"0".parse().unwrap()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("does not hold heights"), "{e}");
        let e = select(p, "t", &channels()[..1], None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("no height channel"), "{e}");
    }
}
