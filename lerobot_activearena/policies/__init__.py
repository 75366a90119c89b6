"""LeRobot policy types shipped by the plugin (config / modeling / processor per policy)."""
