//! Mesh files (OBJ and OFF): reading with errors that name the line, atomic writing.
