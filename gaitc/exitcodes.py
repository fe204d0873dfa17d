"""The exit codes of every gaitc command, in one place (documented in ``gaitc --help``)."""

EXIT_OK = 0  # success; for check/synth: realizable
EXIT_USER = 1  # an error in an input file, or a controller that fails verification
EXIT_USAGE = 2  # the command line is wrong
EXIT_UNREALIZABLE = 3  # check/synth: unrealizable; counter: realizable
EXIT_SOLVER = 4  # the solver could not finish (timeout, memory limit, SLUGS failure)
EXIT_INTERNAL = 70  # a bug in gaitc (GAITC_DEBUG=1 prints the traceback)
