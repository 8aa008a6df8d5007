// The eqmesh WebAssembly decoder as a small JS object: stream bytes in, typed
// arrays (positions, unit normals, TEXCOORD_0 when the stream has an atlas, indices) out, errors as EqmeshError with the
// eqmesh StatusCode name. The wasm module (build-wasm/eqmesh_decoder.mjs, from
// scripts/build-wasm.sh) hands the Draco base chunk to a Draco decoder module,
// which three.js ships in examples/jsm/libs/draco/; loadDracoDecoderModule loads it.

// eqmesh::StatusCode values, for callers that switch on codes.
export const StatusCode = Object.freeze( {
	OK: 0, IO_ERROR: 1, PARSE_ERROR: 2, INVALID_ARGUMENT: 3, INVALID_MESH: 4,
	CORRUPT_STREAM: 5, UNSUPPORTED_VERSION: 6, UNSUPPORTED_FEATURE: 7, RESOURCE_LIMIT: 8, INTERNAL: 9,
} );

export class EqmeshError extends Error {

	constructor( code, codeName, message ) {

		super( `${codeName}: ${message}` );
		this.name = 'EqmeshError';
		this.code = code;
		this.codeName = codeName;

	}

}

// Loads Draco's WebIDL decoder (draco_wasm_wrapper.js + draco_decoder.wasm) from
// `path`. The wrapper is a classic script, not a module, hence the Function call;
// fetching it ourselves keeps the page free of globals.
export async function loadDracoDecoderModule( path ) {

	const base = path.endsWith( '/' ) ? path : path + '/';
	const [ wrapper, wasmBinary ] = await Promise.all( [
		fetchOk( base + 'draco_wasm_wrapper.js' ).then( ( r ) => r.text() ),
		fetchOk( base + 'draco_decoder.wasm' ).then( ( r ) => r.arrayBuffer() ),
	] );
	const factory = new Function( wrapper + '\nreturn DracoDecoderModule;' )();
	return new Promise( ( resolve ) => {

		factory( { wasmBinary, onModuleLoaded: resolve } );

	} );

}

async function fetchOk( url ) {

	const response = await fetch( url );
	if ( ! response.ok ) throw new Error( `${url}: HTTP ${response.status}` );
	return response;

}

// Decodes one Draco mesh buffer to plain arrays, or { error } (never throws past
// here: the C++ side turns the error into a CORRUPT_STREAM status).
function decodeDracoMesh( draco, bytes ) {

	const decoder = new draco.Decoder();
	const mesh = new draco.Mesh();
	try {

		const status = decoder.DecodeArrayToMesh( bytes, bytes.byteLength, mesh );
		if ( ! status.ok() || mesh.ptr === 0 ) return { error: status.error_msg() || 'not a Draco mesh' };
		return readDracoMesh( draco, decoder, mesh );

	} finally {

		draco.destroy( mesh );
		draco.destroy( decoder );

	}

}

function readDracoMesh( draco, decoder, mesh ) {

	const id = decoder.GetAttributeId( mesh, draco.POSITION );
	const attribute = id < 0 ? null : decoder.GetAttribute( mesh, id );
	if ( ! attribute || attribute.num_components() !== 3 ) return { error: 'no 3-component position attribute' };
	const positions = copyFromDraco( draco, mesh.num_points() * 3, Float32Array, ( bytes, ptr ) =>
		decoder.GetAttributeDataArrayForAllPoints( mesh, attribute, draco.DT_FLOAT32, bytes, ptr ) );
	const indices = copyFromDraco( draco, mesh.num_faces() * 3, Uint32Array, ( bytes, ptr ) =>
		decoder.GetTrianglesUInt32Array( mesh, bytes, ptr ) );
	if ( ! positions || ! indices ) return { error: 'could not read the decoded mesh' };
	return { positions, indices };

}

function copyFromDraco( draco, count, Type, fill ) {

	const bytes = count * Type.BYTES_PER_ELEMENT;
	const ptr = draco._malloc( bytes );
	try {

		if ( ! fill( bytes, ptr ) ) return null;
		return new Type( draco.HEAPF32.buffer, ptr, count ).slice();

	} finally {

		draco._free( ptr );

	}

}

export class EqmeshDecoder {

	// `createWasm`: the default export of build-wasm/eqmesh_decoder.mjs;
	// `draco`: a loaded Draco decoder module (loadDracoDecoderModule);
	// `locateFile`: where the .wasm lies when it is not beside the .mjs;
	// `wasmBinary`: the .wasm bytes, where there is nothing to fetch them from.
	static async create( { createWasm, draco, locateFile, wasmBinary } ) {

		if ( ! createWasm || ! draco ) throw new Error( 'EqmeshDecoder.create needs createWasm and draco' );
		const options = { eqmeshDracoDecode: ( bytes ) => decodeDracoMesh( draco, bytes ) };
		if ( locateFile ) options.locateFile = locateFile;
		if ( wasmBinary ) options.wasmBinary = wasmBinary;
		return new EqmeshDecoder( await createWasm( options ) );

	}

	constructor( wasm ) {

		this.wasm = wasm;

	}

	// Full stream (maxLevel -1) or the bytes up to the end of level maxLevel's chunk.
	decode( bytes, maxLevel = - 1 ) {

		return this._withResult( bytes, ( ptr ) => this.wasm._eqm_decode( ptr, bytes.byteLength, maxLevel ),
			( r ) => ( { ...this._layout( r ), ...this._geometry( r ) } ) );

	}

	// The stream header only: levels, coder and the byte length of every chunk.
	readInfo( bytes ) {

		return this._withResult( bytes, ( ptr ) => this.wasm._eqm_read_info( ptr, bytes.byteLength ),
			( r ) => this._layout( r ) );

	}

	_withResult( bytes, call, read ) {

		const w = this.wasm;
		const ptr = w._malloc( Math.max( bytes.byteLength, 1 ) );
		w.HEAPU8.set( bytes, ptr );
		let result = 0;
		try {

			result = call( ptr );
			const code = w._eqm_status( result );
			if ( code !== StatusCode.OK ) {

				throw new EqmeshError( code, w.UTF8ToString( w._eqm_status_name( code ) ),
					w.UTF8ToString( w._eqm_message( result ) ) );

			}
			return read( result );

		} finally {

			if ( result ) w._eqm_free( result );
			w._free( ptr );

		}

	}

	_layout( r ) {

		const w = this.wasm;
		const chunkLengths = [];
		for ( let j = 0; j < w._eqm_chunk_count( r ); j ++ ) chunkLengths.push( w._eqm_chunk_length( r, j ) );
		return { levelsInStream: w._eqm_levels_in_stream( r ), coder: w._eqm_coder( r ), chunkLengths };

	}

	// Copies out of the heap: the next decode may grow (and so detach) it.
	_geometry( r ) {

		const w = this.wasm;
		const vertices = w._eqm_vertex_count( r );
		const indexCount = w._eqm_index_count( r );
		const f32 = ( ptr, n ) => new Float32Array( w.HEAPU8.buffer, ptr, n ).slice();
		const u32 = new Uint32Array( w.HEAPU8.buffer, w._eqm_indices( r ), indexCount );
		const uv = w._eqm_texcoords( r );
		return {
			levelDecoded: w._eqm_level_decoded( r ),
			positions: f32( w._eqm_positions( r ), vertices * 3 ),
			normals: f32( w._eqm_normals( r ), vertices * 3 ),
			texcoords: uv ? f32( uv, vertices * 2 ) : null,
			// ext_spec rule 6: 16-bit indices whenever the level's vertices fit.
			indices: vertices <= 65535 ? Uint16Array.from( u32 ) : u32.slice(),
		};

	}

}
