"""What several test files share: task parameters and fixture constants (``params``), policy training
and play-through runs (``policy_runs``), a fake ``sbatch`` (``fake_slurm``), a headless browser
(``headless_browser``) and the two-process DDP script (``ddp_two_steps``)."""
