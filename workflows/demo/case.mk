# Demo pipeline: scene -> gen-primary -> run-stage (shake) -> post-macro -> VTK + PNG plots.
DEMO_DIR := $(OUT)/demo
DEMO_SCENE := workflows/demo/scene.toml

$(DEMO_DIR)/settled.h5: $(DEMO_SCENE) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(DEMO_SCENE) --out $@

$(DEMO_DIR)/shaken.h5: $(DEMO_SCENE) $(DEMO_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(DEMO_SCENE) --stage shake --in $(DEMO_DIR)/settled.h5 --out $@ \
	  --vtk $(DEMO_DIR)/vtk --checkpoint-every 10000 --restart

$(DEMO_DIR)/displacement.vtu $(DEMO_DIR)/profile.csv &: $(DEMO_DIR)/settled.h5 $(DEMO_DIR)/shaken.h5 $(BIN)/post-macro
	$(BIN)/post-macro --reference $(DEMO_DIR)/settled.h5 --in $(DEMO_DIR)/shaken.h5 \
	  --vtk $(DEMO_DIR)/displacement.vtu --csv $(DEMO_DIR)/profile.csv --axis z --bins 10

$(DEMO_DIR)/profile.png: $(DEMO_DIR)/profile.csv scripts/plot_profile.py scripts/post_table.py
	$(PYTHON) scripts/plot_profile.py $(DEMO_DIR)/profile.csv $@

# Stress in the settled bed: per particle, force chains, coarse-grained fields (kernel width 2 mm,
# about a radius, on a 2 mm grid), a profile along z and its plot.
DEMO_STRESS := $(DEMO_DIR)/stress.vtu $(DEMO_DIR)/chains.vtp $(DEMO_DIR)/fields.vti $(DEMO_DIR)/stress.csv
$(DEMO_STRESS) &: $(DEMO_DIR)/settled.h5 $(BIN)/post-macro
	$(BIN)/post-macro --in $(DEMO_DIR)/settled.h5 --vtk $(DEMO_DIR)/stress.vtu --chains $(DEMO_DIR)/chains.vtp \
	  --grid $(DEMO_DIR)/fields.vti --cell 0.002 --width 0.002 --stress-csv $(DEMO_DIR)/stress.csv --axis z --bins 5

$(DEMO_DIR)/stress.png: $(DEMO_DIR)/stress.csv scripts/plot_stress.py scripts/post_table.py
	$(PYTHON) scripts/plot_stress.py $(DEMO_DIR)/stress.csv $@

CASES += demo
demo-outputs: $(DEMO_DIR)/profile.png $(DEMO_DIR)/displacement.vtu $(DEMO_DIR)/stress.png $(DEMO_STRESS)
