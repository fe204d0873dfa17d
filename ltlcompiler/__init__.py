"""ltlcompiler: the .gait language front end and its lowering to the GR(1) IR."""
