# Quick-start pipeline (a minute): scene -> gen-primary -> run-stage (shake) -> post-macro -> VTK + PNG plots.
QUICK_DIR := $(OUT)/quickstart
QUICK_SCENE := workflows/quickstart/scene.toml

$(QUICK_DIR)/settled.h5: $(QUICK_SCENE) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(QUICK_SCENE) --out $@

$(QUICK_DIR)/shaken.h5: $(QUICK_SCENE) $(QUICK_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(QUICK_SCENE) --stage shake --in $(QUICK_DIR)/settled.h5 --out $@ \
	  --vtk $(QUICK_DIR)/vtk --checkpoint-every 10000 --restart

$(QUICK_DIR)/displacement.vtu $(QUICK_DIR)/profile.csv &: $(QUICK_DIR)/settled.h5 $(QUICK_DIR)/shaken.h5 $(BIN)/post-macro
	$(BIN)/post-macro --reference $(QUICK_DIR)/settled.h5 --in $(QUICK_DIR)/shaken.h5 \
	  --vtk $(QUICK_DIR)/displacement.vtu --csv $(QUICK_DIR)/profile.csv --axis z --bins 10

$(QUICK_DIR)/profile.png: $(QUICK_DIR)/profile.csv scripts/plot_profile.py scripts/post_table.py
	$(PYTHON) scripts/plot_profile.py $(QUICK_DIR)/profile.csv $@

# Stress in the settled bed: per particle, force chains, coarse-grained fields (kernel width 2 mm,
# about a radius, on a 2 mm grid), a profile along z and its plot.
QUICK_STRESS := $(QUICK_DIR)/stress.vtu $(QUICK_DIR)/chains.vtp $(QUICK_DIR)/fields.vti $(QUICK_DIR)/stress.csv
$(QUICK_STRESS) &: $(QUICK_DIR)/settled.h5 $(BIN)/post-macro
	$(BIN)/post-macro --in $(QUICK_DIR)/settled.h5 --vtk $(QUICK_DIR)/stress.vtu --chains $(QUICK_DIR)/chains.vtp \
	  --grid $(QUICK_DIR)/fields.vti --cell 0.002 --width 0.002 --stress-csv $(QUICK_DIR)/stress.csv --axis z --bins 5

$(QUICK_DIR)/stress.png: $(QUICK_DIR)/stress.csv scripts/plot_stress.py scripts/post_table.py
	$(PYTHON) scripts/plot_stress.py $(QUICK_DIR)/stress.csv $@

CASES += quickstart
.PHONY: quickstart
quickstart: build
	@$(MAKE) --no-print-directory -f $(SELF) quickstart-outputs
	@echo "quickstart: VTK series $(QUICK_DIR)/vtk/shake_particles.pvd, displacement $(QUICK_DIR)/displacement.vtu, plot $(QUICK_DIR)/profile.png"
	@echo "quickstart: stress $(QUICK_DIR)/stress.vtu, force chains $(QUICK_DIR)/chains.vtp, fields $(QUICK_DIR)/fields.vti, plot $(QUICK_DIR)/stress.png"
quickstart-outputs: $(QUICK_DIR)/profile.png $(QUICK_DIR)/displacement.vtu $(QUICK_DIR)/stress.png $(QUICK_STRESS)
