# Damping check (thesis §2.4, figs. 2.14-2.15): a sphere released on a wall, against the exact
# damped oscillator, for restitution 0.5 and 1e-7.  make -f Makefile.cases damping-check
DAMP_DIR := $(OUT)/damping-check
DAMP_CASES := eta_0.5 eta_1e-7

$(DAMP_DIR)/%/start.h5: workflows/damping-check/%.toml $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $< --out $@ --quiet

$(DAMP_DIR)/%/dropped.h5 $(DAMP_DIR)/%/track.csv &: workflows/damping-check/%.toml $(DAMP_DIR)/%/start.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $< --stage drop --in $(DAMP_DIR)/$*/start.h5 --out $(DAMP_DIR)/$*/dropped.h5 \
	  --track $(DAMP_DIR)/$*/track.csv --track-ids 0 --track-every 1 --quiet

# The exact oscillator is known to round-off; 1 % of g/ω_d allows the explicit scheme's own error,
# O(γ·ω·Δt + (ω·Δt)²) with ω·Δt ≈ 0.01 here.
$(DAMP_DIR)/%/velocity.png $(DAMP_DIR)/%/summary.csv &: $(DAMP_DIR)/%/start.h5 $(DAMP_DIR)/%/track.csv scripts/damping_check.py
	$(PYTHON) scripts/damping_check.py --checkpoint $(DAMP_DIR)/$*/start.h5 --track $(DAMP_DIR)/$*/track.csv \
	  --summary $(DAMP_DIR)/$*/summary.csv --png $(DAMP_DIR)/$*/velocity.png --check 0.01

.PHONY: damping-check damping-check-outputs
damping-check: build
	@$(MAKE) --no-print-directory -f $(SELF) damping-check-outputs
	@echo "damping-check: plots $(foreach c,$(DAMP_CASES),$(DAMP_DIR)/$(c)/velocity.png)"
damping-check-outputs: $(foreach c,$(DAMP_CASES),$(DAMP_DIR)/$(c)/velocity.png)
# Keep the intermediate files (make would delete them: they come from pattern rules).
.SECONDARY: $(foreach c,$(DAMP_CASES),$(DAMP_DIR)/$(c)/start.h5 $(DAMP_DIR)/$(c)/dropped.h5 $(DAMP_DIR)/$(c)/track.csv)
CASES += damping-check
