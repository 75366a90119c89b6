"""ActiveArena-Bench datasets as LeRobotDataset v3 repos: features, episode recording, sharded
builds (datatrove), merging (LeRobot aggregation) and Hub upload."""
