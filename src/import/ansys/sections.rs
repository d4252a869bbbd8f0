//! The section commands of an archive: `SECTYPE` opens a LINK, SHELL or BEAM section;
//! `SECDATA`, `SECBLOCK` (how CDWRITE writes a shell section's layers), `SECCONTROL` and
//! `SECOFFSET` fill the open one ([`super::shells`], [`super::beams`], [`super::elements`]'s
//! LINK sections).

use super::blocks::{Command, Lines};
use super::elements::LinkSection;
use super::{beams, shells, Archive};
use crate::import::error::ImportError;

impl Archive {
    /// The section commands: `SECTYPE` opens a link, shell or beam section, `SECDATA`,
    /// `SECBLOCK`, `SECCONTROL` and `SECOFFSET` fill the open one.
    pub(super) fn honour_section(
        &mut self,
        file: &str,
        lines: &mut Lines,
        c: &Command,
        refused: &mut Vec<(usize, String)>,
    ) -> Result<(), ImportError> {
        match c.name.as_str() {
            "SECTYPE" => {
                let id = c.int(file, 0)?;
                self.section_now = None;
                self.shell_now = None;
                self.beam_now = None;
                if c.field(1).eq_ignore_ascii_case("BEAM") {
                    match beams::BeamSection::open(c) {
                        Ok(s) => {
                            self.beam_sections.insert(id, s);
                            self.beam_now = Some(id);
                        }
                        Err(why) => refused.push((c.line, why)),
                    }
                } else if c.field(1).eq_ignore_ascii_case("SHELL") {
                    let (s, refusal) = shells::ShellSection::open(c);
                    refused.extend(refusal.map(|why| (c.line, why)));
                    self.shell_sections.insert(id, s);
                    self.shell_now = Some(id);
                } else if c.field(1).eq_ignore_ascii_case("LINK") {
                    let s = LinkSection {
                        line: c.line,
                        area: 0.0,
                        added_mass: 0.0,
                    };
                    self.sections.insert(id, s);
                    self.section_now = Some(id);
                } else {
                    refused.push((
                        c.line,
                        format!(
                            "SECTYPE {id},{}: only LINK (LINK180's), SHELL (SHELL181's) and \
                             BEAM (BEAM188's) sections are read; tapered and other sections' \
                             elements are not formed here",
                            c.field(1)
                        ),
                    ));
                }
            }
            "SECDATA" | "SECCONTROL" if self.shell_now.is_some() => {
                let now = self
                    .shell_now
                    .and_then(|id| self.shell_sections.get_mut(&id));
                if let Some(s) = now {
                    let why = if c.name == "SECDATA" {
                        s.secdata(file, c)?
                    } else {
                        s.seccontrol(file, c)?
                    };
                    refused.extend(why.map(|why| (c.line, why)));
                }
            }
            "SECBLOCK" => {
                // CDWRITE writes a shell section's layers as SECBLOCK,NLAYERS and one record
                // per layer, "thickness, material, angle, integration points", as SECDATA
                let count = c.int(file, 0)?.clamp(0, 10_000) as usize;
                match self
                    .shell_now
                    .and_then(|id| self.shell_sections.get_mut(&id))
                {
                    Some(s) => {
                        for _ in 0..count {
                            let (n, text) = lines.record(c.line, "SECBLOCK")?;
                            let layer = Command {
                                line: n,
                                name: "SECBLOCK".into(),
                                fields: text.split(',').map(str::trim).collect(),
                            };
                            refused.extend(s.secdata(file, &layer)?.map(|why| (n, why)));
                        }
                    }
                    None => {
                        refused.push((
                            c.line,
                            "SECBLOCK of a section other than a shell (a beam section's own \
                             mesh): not read (ANSYS integrates over it; ASEC, RECT, CSOLID and \
                             CTUBE beam sections are read)"
                                .into(),
                        ));
                        lines.skip_data_lines();
                    }
                }
            }
            "SECDATA" | "SECCONTROL" if self.beam_now.is_some() => {
                let now = self.beam_now.and_then(|id| self.beam_sections.get_mut(&id));
                if let Some(why) = now.map(|s| s.read(file, c)).transpose()?.flatten() {
                    refused.push((c.line, why));
                }
            }
            "SECOFFSET" => {
                let beam = self.beam_now.and_then(|id| self.beam_sections.get_mut(&id));
                let why = match (self.shell_now, beam) {
                    (Some(id), _) => {
                        (self.shell_sections.get_mut(&id)).and_then(|s| s.secoffset(c))
                    }
                    (None, Some(b)) => b.secoffset(c),
                    (None, None) => {
                        Some("SECOFFSET of a section other than a shell or beam: not read".into())
                    }
                };
                refused.extend(why.map(|why| (c.line, why)));
            }
            // the data of a section not read is not read either (its SECTYPE is refused)
            "SECDATA" | "SECCONTROL" => {
                let value = c.real(file, 0)?;
                if let Some(s) = self.section_now.and_then(|id| self.sections.get_mut(&id)) {
                    if c.name == "SECDATA" {
                        s.area = value;
                    } else {
                        s.added_mass = value;
                    }
                }
            }
            _ => return Err(super::unread_honoured(file, c)),
        }
        Ok(())
    }
}
