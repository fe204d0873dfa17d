# gr1c -n ALL_INIT
# gr1c specification written by gaitc from peers_small
# initial condition: direct form (see peers/spc.py)
ENV: door sensor [0,2];
SYS: pos [0,3] light;
ENVINIT:
  # structuredslugs [ENV_INIT] (tests/golden/peers_small.structuredslugs:12:1)
  !door
  # structuredslugs [ENV_INIT] (tests/golden/peers_small.structuredslugs:13:1)
  & sensor = 0;
SYSINIT:
  # structuredslugs [SYS_INIT] (tests/golden/peers_small.structuredslugs:22:1)
  pos = 0
  # structuredslugs [SYS_INIT] (tests/golden/peers_small.structuredslugs:23:1)
  & (light <-> door);
ENVTRANS:
  # structuredslugs [ENV_TRANS] (tests/golden/peers_small.structuredslugs:16:1)
  [](sensor' <= 1 | (sensor' = 2 & sensor >= 1));
SYSTRANS:
  # structuredslugs [SYS_TRANS] (tests/golden/peers_small.structuredslugs:26:1)
  [](((pos' = 1 & pos = 0) | (pos' = 2 & pos = 1) | (pos' = 3 & pos = 2)) | ((pos' = 0 & pos = 0) | (pos' = 1 & pos = 1) | (pos' = 2 & pos = 2) | (pos' = 3 & pos = 3)))
  # structuredslugs [SYS_TRANS] (tests/golden/peers_small.structuredslugs:27:1)
  & [](!(light' <-> (door' | (pos' = 0 | (pos' = 1 & sensor' >= 1) | (pos' = 2 & sensor' = 2)))));
ENVGOAL:
  # structuredslugs [ENV_LIVENESS] (tests/golden/peers_small.structuredslugs:19:1)
  []<>(!door);
SYSGOAL:
  # structuredslugs [SYS_LIVENESS] (tests/golden/peers_small.structuredslugs:30:1)
  []<>(pos = 3)
  # structuredslugs [SYS_LIVENESS] (tests/golden/peers_small.structuredslugs:31:1)
  & []<>(light);
