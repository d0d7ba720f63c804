//! Exchange formats of tabulated BRDFs: import of the Cornell ASTM measurements, MERL `.binary`
//! and CSV samples; export to MERL, the Mitsuba 3 / pbrt-v4 tensor `.bsdf`, Radiance's XML BSDF
//! (tensor tree), Radiance PAB-Opto data files and CSV. Scattered samples become tables through [`scattered`].

pub mod astm;
pub mod csv;
pub mod lobe_model;
pub mod merl;
pub mod mitsuba;
pub mod pabopto;
pub mod radiance_xml;
pub mod scattered;
pub mod tensor;
