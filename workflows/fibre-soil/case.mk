# Fibre-reinforced soil: triaxial compression of one sample with 0 %, 0.5 % and 1 % of fibres
# (workflows/fibre-soil/README.md).
#   make -f Makefile.cases fibre-soil   fill and consolidate 2,000 spheres to 100 kPa, shear them
#                                       three times to 15 % axial strain, report; and the rate check:
#                                       the small sample (400 spheres) at the platen speed and at half
FS_DIR := $(OUT)/fibre-soil
FS_SCENE := workflows/fibre-soil/scene.toml
FS_SMALL := workflows/fibre-soil/small_scene.sh
FS_STAGES := shear_0 shear_05 shear_1
FS_REPORT := $(PYTHON) scripts/triaxial_report.py
# The fibres' cross-section pi d^2 / 4 for d = 0.3 mm (the scene's diameter): mean fibre stress.
FS_AREA := 7.0686e-8

$(FS_DIR)/filled.h5: $(FS_SCENE) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(FS_SCENE) --out $@

$(FS_DIR)/consolidated.h5: $(FS_SCENE) $(FS_DIR)/filled.h5 $(BIN)/compact
	$(BIN)/compact --scene $(FS_SCENE) --in $(FS_DIR)/filled.h5 --out $@

# Each shear from the same consolidated sample; the wall log every 200 steps (forces and positions
# of the six faces), VTK frames (particles and fibres) every 1.5 % of axial strain.
define FS_SHEAR
$(FS_DIR)/$(1).h5 $(FS_DIR)/$(1).walls.csv &: $(FS_SCENE) $(FS_DIR)/consolidated.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(FS_SCENE) --stage $(1) --in $(FS_DIR)/consolidated.h5 --out $(FS_DIR)/$(1).h5 \
	  --wall-forces $(FS_DIR)/$(1).walls.csv --wall-forces-every 200 --vtk $(FS_DIR)/vtk
endef
$(foreach s,$(FS_STAGES),$(eval $(call FS_SHEAR,$(s))))

$(FS_DIR)/summary.csv $(FS_DIR)/curves.png $(FS_DIR)/curves.csv $(FS_DIR)/gain.png $(FS_DIR)/fibre_tension.png &: \
    $(foreach s,$(FS_STAGES),$(FS_DIR)/$(s).walls.csv) scripts/triaxial_report.py scripts/post_table.py
	$(FS_REPORT) --run "0 %:0:$(FS_DIR)/shear_0.walls.csv" --run "0.5 %:0.005:$(FS_DIR)/shear_05.walls.csv:$(FS_DIR)/vtk/shear_05_fibres.pvd" \
	  --run "1 %:0.01:$(FS_DIR)/shear_1.walls.csv:$(FS_DIR)/vtk/shear_1_fibres.pvd" --fibre-area $(FS_AREA) \
	  --summary $(FS_DIR)/summary.csv --curves $(FS_DIR)/curves.png --curves-csv $(FS_DIR)/curves.csv \
	  --gain $(FS_DIR)/gain.png --fibres $(FS_DIR)/fibre_tension.png

# The coarse-grained stress of the 1 % sample at the end, fibres included (docs/post.md): a 3 mm grid.
$(FS_DIR)/fields_1.vti: $(FS_DIR)/shear_1.h5 $(BIN)/post-macro
	$(BIN)/post-macro --in $(FS_DIR)/shear_1.h5 --grid $@ --cell 0.003 --width 0.003 --average-csv $(FS_DIR)/average_1.csv

# Quasi-static check at the small size: the unreinforced shear at the platen speed and at half.
$(FS_DIR)/small/full.toml: $(FS_SCENE) $(FS_SMALL)
	@mkdir -p $(@D)
	bash $(FS_SMALL) $(FS_SCENE) > $@.tmp && mv $@.tmp $@
$(FS_DIR)/small/half.toml: $(FS_SCENE) $(FS_SMALL)
	@mkdir -p $(@D)
	bash $(FS_SMALL) $(FS_SCENE) half > $@.tmp && mv $@.tmp $@
$(FS_DIR)/small/filled.h5: $(FS_DIR)/small/full.toml $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $< --out $@
$(FS_DIR)/small/consolidated.h5: $(FS_DIR)/small/full.toml $(FS_DIR)/small/filled.h5 $(BIN)/compact
	$(BIN)/compact --scene $< --in $(FS_DIR)/small/filled.h5 --out $@
$(FS_DIR)/small/%.walls.csv: $(FS_DIR)/small/%.toml $(FS_DIR)/small/consolidated.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $< --stage shear_0 --in $(FS_DIR)/small/consolidated.h5 --out $(FS_DIR)/small/$*.h5 \
	  --wall-forces $@ --wall-forces-every 100
$(FS_DIR)/rate.csv $(FS_DIR)/rate.png &: $(FS_DIR)/small/full.walls.csv $(FS_DIR)/small/half.walls.csv scripts/triaxial_report.py
	$(FS_REPORT) --run "platens 15 mm/s:0:$(FS_DIR)/small/full.walls.csv" --run "7.5 mm/s:0:$(FS_DIR)/small/half.walls.csv" \
	  --summary $(FS_DIR)/rate.csv --curves $(FS_DIR)/rate.png

.PHONY: fibre-soil fibre-soil-outputs
fibre-soil: build
	@$(MAKE) --no-print-directory -f $(SELF) fibre-soil-outputs
	@echo "fibre-soil: $(FS_DIR)/summary.csv, curves.png/.csv, gain.png, fibre_tension.png, fields_1.vti; rate check $(FS_DIR)/rate.csv/.png"
fibre-soil-outputs: $(FS_DIR)/summary.csv $(FS_DIR)/fields_1.vti $(FS_DIR)/rate.csv
CASES += fibre-soil
