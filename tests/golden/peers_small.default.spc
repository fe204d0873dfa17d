# gr1c -n ALL_INIT
# gr1c specification written by gaitc from peers_small
# initial condition: started form (see peers/spc.py)
ENV: door sensor [0,2];
SYS: pos [0,3] light gaitc_started;
SYSINIT:
  # gaitc: before the game starts
  !gaitc_started;
ENVTRANS:
  # gaitc: the environment's first move: θe on the first state
  [](!gaitc_started -> (!door' & sensor' = 0))
  # structuredslugs [ENV_TRANS] (tests/golden/peers_small.structuredslugs:16:1)
  & [](gaitc_started -> (sensor' <= 1 | (sensor' = 2 & sensor >= 1)));
SYSTRANS:
  # gaitc: the system's first move: θs on the first state; the game starts
  [](!gaitc_started -> (gaitc_started' & (pos' = 0 & (light' <-> door'))))
  # gaitc: the game goes on
  & [](gaitc_started -> gaitc_started')
  # structuredslugs [SYS_TRANS] (tests/golden/peers_small.structuredslugs:26:1)
  & [](gaitc_started -> (((pos' = 1 & pos = 0) | (pos' = 2 & pos = 1) | (pos' = 3 & pos = 2)) | ((pos' = 0 & pos = 0) | (pos' = 1 & pos = 1) | (pos' = 2 & pos = 2) | (pos' = 3 & pos = 3))))
  # structuredslugs [SYS_TRANS] (tests/golden/peers_small.structuredslugs:27:1)
  & [](gaitc_started -> !(light' <-> (door' | (pos' = 0 | (pos' = 1 & sensor' >= 1) | (pos' = 2 & sensor' = 2)))));
ENVGOAL:
  # structuredslugs [ENV_LIVENESS] (tests/golden/peers_small.structuredslugs:19:1)
  []<>(!door);
SYSGOAL:
  # structuredslugs [SYS_LIVENESS] (tests/golden/peers_small.structuredslugs:30:1)
  []<>(pos = 3)
  # structuredslugs [SYS_LIVENESS] (tests/golden/peers_small.structuredslugs:31:1)
  & []<>(light);
