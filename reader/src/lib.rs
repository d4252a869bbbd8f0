//! flexbody-reader: see format-spec/.
