"""What every ActiveArena-VLA head shares (not a policy type): the config fields, the policy base
(backbone, sequence assembly, state tokens, memory bank, think loss, greedy decoding, evaluation
loop), the processors, dataset annotations, backbone loading and the tiny test backbone."""
