//! Triangle operators (in progress).
