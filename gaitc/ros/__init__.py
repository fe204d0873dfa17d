"""The controller on ROS 2: the topic layout, the controller node, the simulated robot node
and MCAP recordings of runs (the ``ros`` extra: ``pip install 'gaitc[ros]'``)."""
